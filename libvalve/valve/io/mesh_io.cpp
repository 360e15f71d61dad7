#include "valve/io/mesh_io.hpp"

#include <vtkCellArray.h>
#include <vtkLogger.h>
#include <vtkOutputWindow.h>
#include <vtkCellData.h>
#include <vtkDataSetSurfaceFilter.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkGenericDataObjectReader.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkOBJReader.h>
#include <vtkOBJWriter.h>
#include <vtkPLYReader.h>
#include <vtkPLYWriter.h>
#include <vtkPointData.h>
#include <vtkPointSet.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataWriter.h>
#include <vtkSTLReader.h>
#include <vtkSTLWriter.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkTransform.h>
#include <vtkTransformPolyDataFilter.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "valve/core/atomic_file.hpp"
#include "valve/core/error.hpp"

namespace valve {
namespace fs = std::filesystem;

namespace {

// Largest coordinate magnitude read (mm): a kilometre is no valve, and 1e300 would overflow
// the squares and cross products of every geometric query into inf and NaN.
constexpr double kMaxCoordinateMm = 1e6;

std::string describe_point(const Eigen::RowVector3d& p) {
  return "(" + format_number(p[0]) + ", " + format_number(p[1]) + ", " + format_number(p[2]) + ")";
}

std::string lower_extension(const fs::path& p) {
  std::string e = p.extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
  return e;
}

vtkSmartPointer<vtkPolyData> to_polydata(vtkDataSet* ds) {
  if (auto* pd = vtkPolyData::SafeDownCast(ds)) return pd;
  vtkNew<vtkDataSetSurfaceFilter> surf;
  surf->SetInputData(ds);
  surf->Update();
  return surf->GetOutput();
}

// Counts the errors VTK reports while it lives, printing nothing: installed as VTK's output
// window (with warnings displayed, or VTK would not report at all), the previous window and
// setting restored on destruction.
class CountingOutputWindow : public vtkOutputWindow {
 public:
  static CountingOutputWindow* New();
  vtkTypeMacro(CountingOutputWindow, vtkOutputWindow);
  void DisplayText(const char*) override {}
  void DisplayErrorText(const char*) override { ++errors; }
  int errors = 0;
};
vtkStandardNewMacro(CountingOutputWindow);

class ReadErrorCapture {
 public:
  ReadErrorCapture() : previous_(vtkOutputWindow::GetInstance()), display_(vtkObject::GetGlobalWarningDisplay()) {
    vtkOutputWindow::SetInstance(window_);
    vtkObject::GlobalWarningDisplayOn();
    // VTK 9 also logs errors to stderr itself; the stages report in one line of their own.
    // Left off for the process, as read_polydata leaves GlobalWarningDisplay off.
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  }
  ~ReadErrorCapture() {
    vtkObject::SetGlobalWarningDisplay(display_);
    vtkOutputWindow::SetInstance(previous_);
  }
  ReadErrorCapture(const ReadErrorCapture&) = delete;
  ReadErrorCapture& operator=(const ReadErrorCapture&) = delete;
  bool seen() const { return window_->errors > 0; }

 private:
  vtkSmartPointer<vtkOutputWindow> previous_;
  vtkNew<CountingOutputWindow> window_;
  int display_;
};

// The coordinate system a file declares, as 3D Slicer writes it (vtkMRMLModelStorageNode):
// the field-data string array SPACE in .vtp and .vtu, "SPACE=RAS|LPS" in the legacy .vtk and
// STL headers, a PLY comment and the first OBJ comment. `tag` is that field value or header
// text. A file without the tag is in our frame, LPS; any other value is refused rather than
// guessed, since a wrong guess mirrors the valve silently.
bool declares_ras(const std::string& file, const std::string& tag, bool is_field) {
  std::string value = tag;
  if (!is_field) {
    const auto at = tag.find("SPACE=");
    if (at == std::string::npos) return false;
    value = tag.substr(at + 6, tag.find_first_of(" \t\r\n,;", at + 6) - (at + 6));
  }
  if (value != "RAS" && value != "LPS")
    throw_input_error(file, "SPACE", "RAS or LPS", "\"" + value + "\"");
  return value == "RAS";
}

// The SPACE field of an XML data set, as a tag for declares_ras.
bool field_declares_ras(const std::string& file, vtkDataSet* ds) {
  vtkAbstractArray* a = ds->GetFieldData()->GetAbstractArray("SPACE");
  if (!a) return false;
  auto* s = vtkStringArray::SafeDownCast(a);
  return declares_ras(file, s && s->GetNumberOfValues() > 0 ? s->GetValue(0) : "", true);
}

// RAS to LPS (x and y negated), transforming what Slicer's own conversion transforms (points,
// active normals and vectors) so that a mesh Slicer converted on writing comes back exactly.
vtkSmartPointer<vtkPolyData> ras_to_lps(vtkPolyData* pd) {
  vtkNew<vtkTransform> flip;
  flip->Scale(-1, -1, 1);
  vtkNew<vtkTransformPolyDataFilter> f;
  f->SetTransform(flip);
  f->SetInputData(pd);
  f->Update();
  return f->GetOutput();
}

vtkSmartPointer<vtkPolyData> read_polydata(const fs::path& path) {
  // VTK's own multi-line messages would break the one-line error contract; we check every
  // result ourselves and report in one line.
  vtkObject::GlobalWarningDisplayOff();
  const std::string file = path.string();
  if (!fs::exists(path)) throw_input_error(file, "", "an existing mesh file", "no such file");
  const std::string ext = lower_extension(path);
  vtkSmartPointer<vtkDataSet> ds;
  std::string header;      // Slicer's "SPACE=..." in a header or comment
  bool has_field = false;  // XML formats carry the SPACE field instead
  // VTK readers report a truncated or corrupt file through the output window (often from
  // their XML parser, not the reader) and return what they got, often no cells; without
  // this the complaint would be about the missing cells.
  const ReadErrorCapture errors;
  // VTK readers print to stderr and return empty data on failure; check the result.
  if (ext == ".vtp") {
    vtkNew<vtkXMLPolyDataReader> r;
    r->SetFileName(file.c_str());
    if (!r->CanReadFile(file.c_str())) throw_input_error(file, "", "a VTK XML PolyData file", "unreadable content");
    r->Update();
    ds = r->GetOutput();
    has_field = true;
  } else if (ext == ".vtu") {
    vtkNew<vtkXMLUnstructuredGridReader> r;
    r->SetFileName(file.c_str());
    if (!r->CanReadFile(file.c_str())) throw_input_error(file, "", "a VTK XML UnstructuredGrid file", "unreadable content");
    r->Update();
    ds = r->GetOutput();
    has_field = true;
  } else if (ext == ".vtk") {
    vtkNew<vtkGenericDataObjectReader> r;
    r->SetFileName(file.c_str());
    r->Update();
    ds = vtkDataSet::SafeDownCast(r->GetOutput());
    if (!ds) throw_input_error(file, "", "a legacy VTK data set", "unreadable content");
    header = r->GetHeader() ? r->GetHeader() : "";
  } else if (ext == ".stl") {
    vtkNew<vtkSTLReader> r;
    r->SetFileName(file.c_str());
    r->Update();
    ds = r->GetOutput();
    header = r->GetHeader() ? r->GetHeader() : "";
  } else if (ext == ".ply") {
    vtkNew<vtkPLYReader> r;
    r->SetFileName(file.c_str());
    if (!r->CanReadFile(file.c_str())) throw_input_error(file, "", "a PLY file", "unreadable content");
    r->Update();
    ds = r->GetOutput();
    for (vtkIdType k = 0; k < r->GetComments()->GetNumberOfValues(); ++k)
      if (r->GetComments()->GetValue(k).find("SPACE=") != std::string::npos) header = r->GetComments()->GetValue(k);
  } else if (ext == ".obj") {
    vtkNew<vtkOBJReader> r;
    r->SetFileName(file.c_str());
    r->Update();
    ds = r->GetOutput();
    header = r->GetComment() ? r->GetComment() : "";
  } else {
    throw_input_error(file, "extension", ".vtp|.vtk|.vtu|.stl|.ply|.obj", "\"" + ext + "\"");
  }
  if (!ds) throw_input_error(file, "", "a mesh", "nothing readable");
  if (errors.seen()) throw_input_error(file, "", "a complete mesh file", "a read error (truncated or corrupt content)");
  const bool ras = has_field ? field_declares_ras(file, ds) : declares_ras(file, header, false);
  vtkSmartPointer<vtkPolyData> pd = to_polydata(ds);
  return ras ? ras_to_lps(pd) : pd;
}

void add_int_point_array(vtkPolyData* pd, const char* name, const std::vector<int>& v) {
  vtkNew<vtkIntArray> a;
  a->SetName(name);
  a->SetNumberOfValues(static_cast<vtkIdType>(v.size()));
  for (size_t i = 0; i < v.size(); ++i) a->SetValue(static_cast<vtkIdType>(i), v[i]);
  pd->GetPointData()->AddArray(a);
}

void add_double_array(vtkDataSetAttributes* attr, const std::string& name, const Eigen::MatrixXd& m) {
  vtkNew<vtkDoubleArray> a;
  a->SetName(name.c_str());
  a->SetNumberOfComponents(static_cast<int>(m.cols()));
  a->SetNumberOfTuples(m.rows());
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index c = 0; c < m.cols(); ++c) {
      // No NaN is written silently: non-finite values are an error upstream.
      if (!std::isfinite(m(i, c))) throw NumericalError("write_mesh: array " + name + " has a non-finite value");
      a->SetComponent(i, static_cast<int>(c), m(i, c));
    }
  attr->AddArray(a);
}

}  // namespace

MatX3 read_point_positions(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw_input_error(path.string(), "", "a .vtu or .vtp file", "nothing there");
  vtkSmartPointer<vtkPointSet> data;
  const std::string ext = path.extension().string();
  vtkObject::GlobalWarningDisplayOff();  // VTK's multi-line warnings; we report one line
  if (ext == ".vtu") {
    auto reader = vtkSmartPointer<vtkXMLUnstructuredGridReader>::New();
    if (!reader->CanReadFile(path.string().c_str())) throw_input_error(path.string(), "", "a VTK XML UnstructuredGrid file", "unreadable content");
    reader->SetFileName(path.string().c_str());
    reader->Update();
    data = reader->GetOutput();
  } else if (ext == ".vtp") {
    auto reader = vtkSmartPointer<vtkXMLPolyDataReader>::New();
    if (!reader->CanReadFile(path.string().c_str())) throw_input_error(path.string(), "", "a VTK XML PolyData file", "unreadable content");
    reader->SetFileName(path.string().c_str());
    reader->Update();
    data = reader->GetOutput();
  } else {
    throw_input_error(path.string(), "", "a .vtu or .vtp file", "\"" + ext + "\"");
  }
  if (!data || !data->GetPoints() || data->GetNumberOfPoints() == 0)
    throw_input_error(path.string(), "", "points", "none (unreadable or empty)");
  const double mirror = field_declares_ras(path.string(), data) ? -1 : 1;
  MatX3 x(data->GetNumberOfPoints(), 3);
  for (vtkIdType i = 0; i < data->GetNumberOfPoints(); ++i) {
    double p[3];
    data->GetPoint(i, p);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      throw_input_error(path.string(), "point " + std::to_string(i), "finite coordinates", "NaN or infinity");
    x.row(i) << mirror * p[0], mirror * p[1], p[2];
  }
  return x;
}

std::vector<std::pair<Vec3, Vec3>> read_line_segments(const fs::path& path) {
  const std::string file = path.string();
  vtkSmartPointer<vtkPolyData> pd = read_polydata(path);
  if (pd->GetNumberOfLines() == 0) throw_input_error(file, "lines", "line cells", "none");
  std::vector<std::pair<Vec3, Vec3>> segments;
  auto point = [&](vtkIdType i) {
    double p[3];
    pd->GetPoint(i, p);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      throw_input_error(file, "point " + std::to_string(i), "finite coordinates", "NaN or infinity");
    return Vec3(p[0], p[1], p[2]);
  };
  vtkCellArray* lines = pd->GetLines();
  lines->InitTraversal();
  vtkIdType n;
  const vtkIdType* ids;
  while (lines->GetNextCell(n, ids))
    for (vtkIdType k = 0; k + 1 < n; ++k) segments.emplace_back(point(ids[k]), point(ids[k + 1]));
  return segments;
}

TriMesh read_mesh(const fs::path& path, std::vector<NamedArray>* extra) {
  const std::string file = path.string();
  vtkSmartPointer<vtkPolyData> pd = read_polydata(path);
  TriMesh m;
  const vtkIdType np = pd->GetNumberOfPoints();
  m.points.resize(np, 3);
  for (vtkIdType i = 0; i < np; ++i) {
    double p[3];
    pd->GetPoint(i, p);
    m.points.row(i) << p[0], p[1], p[2];
    // Squares and cross products of coordinates must not overflow downstream.
    if (!m.points.row(i).allFinite() || m.points.row(i).cwiseAbs().maxCoeff() > kMaxCoordinateMm)
      throw_input_error(file, "point " + std::to_string(i), "finite coordinates within ±1e6 mm",
                        describe_point(m.points.row(i)));
  }
  if (pd->GetNumberOfVerts() + pd->GetNumberOfLines() > 0 && pd->GetNumberOfPolys() == 0)
    throw_input_error(file, "cells", "triangles", "only vertices or lines");
  if (pd->GetNumberOfStrips() > 0) throw_input_error(file, "cells", "triangles", "triangle strips");
  vtkCellArray* polys = pd->GetPolys();
  vtkNew<vtkIdList> ids;
  polys->InitTraversal();
  vtkIdType cell = 0;
  while (polys->GetNextCell(ids)) {
    if (ids->GetNumberOfIds() != 3)
      throw_input_error(file, "cell " + std::to_string(cell), "a triangle",
                        "a polygon with " + std::to_string(ids->GetNumberOfIds()) + " points");
    for (int k = 0; k < 3; ++k)
      if (ids->GetId(k) < 0 || ids->GetId(k) >= np)
        throw_input_error(file, "cell " + std::to_string(cell), "point indices in [0, " + std::to_string(np - 1) + "]",
                          std::to_string(ids->GetId(k)));
    m.triangles.emplace_back(static_cast<int>(ids->GetId(0)), static_cast<int>(ids->GetId(1)),
                             static_cast<int>(ids->GetId(2)));
    ++cell;
  }
  if (m.triangles.empty()) throw_input_error(file, "cells", "at least one triangle", "none");
  // The cell data of a polydata is ordered verts, lines, polys, strips: polys come first
  // here because we rejected verts and lines above.
  // The arrays this project writes must have its shape when present: a file whose array was
  // cut short or mislabelled is an error, not a mesh read without it.
  auto shaped = [&](vtkDataArray* a, const char* name, int components, vtkIdType tuples, const char* per) {
    if (!a) return false;
    if (a->GetNumberOfComponents() != components || a->GetNumberOfTuples() != tuples)
      throw_input_error(file, name,
                        std::to_string(tuples) + " tuples of " + std::to_string(components) + " (one per " + per + ")",
                        std::to_string(a->GetNumberOfTuples()) + " tuples of " + std::to_string(a->GetNumberOfComponents()));
    for (vtkIdType i = 0; i < tuples; ++i)
      for (int c = 0; c < components; ++c)
        if (!std::isfinite(a->GetComponent(i, c)))
          throw_input_error(file, std::string(name) + " of " + per + " " + std::to_string(i), "finite values", "NaN or infinity");
    return true;
  };
  // An integer label stored in a float array must be a whole number in [lo, hi].
  auto label = [&](vtkDataArray* a, vtkIdType i, const char* name, const char* per, double lo, double hi,
                   const std::string& expected) {
    const double v = a->GetComponent(i, 0);
    if (v != std::floor(v) || v < lo || v > hi)
      throw_input_error(file, std::string(name) + " of " + per + " " + std::to_string(i), expected, format_number(v));
    return static_cast<int>(v);
  };
  if (auto* fib = pd->GetCellData()->GetArray("FiberDirection"); shaped(fib, "FiberDirection", 3, m.num_triangles(), "cell")) {
    m.fiber.resize(m.num_triangles(), 3);
    for (int t = 0; t < m.num_triangles(); ++t)
      for (int c = 0; c < 3; ++c) m.fiber(t, c) = fib->GetComponent(t, c);
  }
  if (auto* a = pd->GetPointData()->GetArray("NodeRole"); shaped(a, "NodeRole", 1, np, "point"))
    for (vtkIdType i = 0; i < np; ++i)
      m.roles.push_back(static_cast<NodeRole>(label(a, i, "NodeRole", "point", 0, 2, "0 (free), 1 (fixed) or 2 (prescribed)")));
  if (auto* a = pd->GetPointData()->GetArray("BoundaryType"); shaped(a, "BoundaryType", 1, np, "point"))
    for (vtkIdType i = 0; i < np; ++i)
      m.boundary.push_back(static_cast<BoundaryType>(
          label(a, i, "BoundaryType", "point", 0, 2, "0 (interior), 1 (attached) or 2 (free edge)")));
  if (auto* a = pd->GetCellData()->GetArray("Leaflet"); shaped(a, "Leaflet", 1, m.num_triangles(), "cell"))
    for (int t = 0; t < m.num_triangles(); ++t)
      m.leaflet.push_back(label(a, t, "Leaflet", "cell", 0, 1e6, "a leaflet index in [0, 1e6]"));
  if (auto* a = pd->GetPointData()->GetArray("InitialDisplacement"); shaped(a, "InitialDisplacement", 3, np, "point")) {
    m.initial = m.points;
    for (vtkIdType i = 0; i < np; ++i)
      for (int c = 0; c < 3; ++c) m.initial(i, c) += a->GetComponent(i, c);
    if (!m.initial.allFinite()) throw_input_error(file, "InitialDisplacement", "finite values", "NaN or infinity");
  }
  if (extra) {
    // Every named array as it is in the file: point data, then cell data (per_cell).
    auto collect = [&](vtkDataSetAttributes* data, bool per_cell) {
      for (int k = 0; k < data->GetNumberOfArrays(); ++k) {
        vtkDataArray* a = data->GetArray(k);
        if (!a || !a->GetName()) continue;
        NamedArray na{a->GetName(), Eigen::MatrixXd(a->GetNumberOfTuples(), a->GetNumberOfComponents()), per_cell};
        for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
          for (int c = 0; c < a->GetNumberOfComponents(); ++c) na.values(i, c) = a->GetComponent(i, c);
        extra->push_back(std::move(na));
      }
    };
    collect(pd->GetPointData(), false);
    collect(pd->GetCellData(), true);
  }
  m.fill_defaults();
  return m;
}

namespace {

// Points (doubles) of a poly data from rows of x.
void set_points(vtkPolyData* pd, const MatX3& x) {
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(x.rows());
  for (Eigen::Index i = 0; i < x.rows(); ++i) pts->SetPoint(i, x(i, 0), x(i, 1), x(i, 2));
  pd->SetPoints(pts);
}

// The caller's named arrays (checked against the point and cell counts) and SPACE=LPS.
void add_named_arrays(vtkPolyData* pd, const std::vector<NamedArray>& arrays, Eigen::Index cells, const char* who) {
  for (const auto& a : arrays) {
    const Eigen::Index expected = a.per_cell ? cells : pd->GetNumberOfPoints();
    if (a.values.rows() != expected) throw Error(std::string(who) + ": array " + a.name + " has the wrong length");
    add_double_array(a.per_cell ? static_cast<vtkDataSetAttributes*>(pd->GetCellData())
                                : static_cast<vtkDataSetAttributes*>(pd->GetPointData()),
                     a.name, a.values);
  }
  vtkNew<vtkStringArray> space;
  space->SetName("SPACE");
  space->InsertNextValue("LPS");
  pd->GetFieldData()->AddArray(space);
}

void write_vtp(const fs::path& path, const fs::path& tmp, vtkPolyData* pd) {
  vtkNew<vtkXMLPolyDataWriter> w;
  w->SetFileName(tmp.string().c_str());
  w->SetInputData(pd);
  w->SetDataModeToAppended();
  w->EncodeAppendedDataOff();
  if (w->Write() != 1) throw Error(path.string() + ": VTK could not write the file");
}

template <class Writer, class Configure>
int write_with(const fs::path& tmp, vtkPolyData* pd, Configure configure) {
  vtkNew<Writer> w;
  w->SetFileName(tmp.string().c_str());
  w->SetInputData(pd);
  configure(w.Get());
  return w->Write();
}

// The mesh as VTK poly data with its arrays, built once for every format it is written in.
vtkSmartPointer<vtkPolyData> mesh_polydata(const fs::path& path, const TriMesh& mesh, const MatX3* positions,
                                           const std::vector<NamedArray>& extra) {
  const MatX3& x = positions ? *positions : mesh.points;
  if (!x.allFinite()) throw NumericalError(path.string() + ": refusing to write non-finite coordinates");
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  set_points(pd, x);
  vtkNew<vtkCellArray> polys;
  for (const auto& t : mesh.triangles) {
    const vtkIdType ids[3] = {t[0], t[1], t[2]};
    polys->InsertNextCell(3, ids);
  }
  pd->SetPolys(polys);
  if (mesh.fiber.rows() == mesh.num_triangles()) add_double_array(pd->GetCellData(), "FiberDirection", mesh.fiber);
  if (static_cast<int>(mesh.roles.size()) == mesh.num_nodes()) {
    std::vector<int> r(mesh.roles.size());
    std::transform(mesh.roles.begin(), mesh.roles.end(), r.begin(), [](NodeRole v) { return static_cast<int>(v); });
    add_int_point_array(pd, "NodeRole", r);
  }
  if (static_cast<int>(mesh.boundary.size()) == mesh.num_nodes()) {
    std::vector<int> b(mesh.boundary.size());
    std::transform(mesh.boundary.begin(), mesh.boundary.end(), b.begin(), [](BoundaryType v) { return static_cast<int>(v); });
    add_int_point_array(pd, "BoundaryType", b);
  }
  if (static_cast<int>(mesh.leaflet.size()) == mesh.num_triangles()) {
    vtkNew<vtkIntArray> a;
    a->SetName("Leaflet");
    a->SetNumberOfValues(mesh.num_triangles());
    for (int t = 0; t < mesh.num_triangles(); ++t) a->SetValue(t, mesh.leaflet[t]);
    pd->GetCellData()->AddArray(a);
  }
  if (!positions && mesh.initial.rows() == mesh.num_nodes()) {
    const MatX3 d = mesh.initial - mesh.points;
    add_double_array(pd->GetPointData(), "InitialDisplacement", d);
  }
  add_named_arrays(pd, extra, mesh.num_triangles(), "write_mesh");
  return pd;
}

// The extension, lower case, if write_polydata writes it; else an InputError naming `path`.
std::string mesh_write_extension(const fs::path& path) {
  const std::string ext = lower_extension(path);
  if (std::find(kMeshWriteExtensions.begin(), kMeshWriteExtensions.end(), ext) == kMeshWriteExtensions.end())
    throw_input_error(path.string(), "extension", ".vtp|.vtk|.stl|.ply|.obj", "\"" + ext + "\"");
  return ext;
}

void write_polydata(const fs::path& path, vtkPolyData* pd) {
  const std::string ext = mesh_write_extension(path);
  write_via_temp(path, [&](const fs::path& tmp) {
    if (ext == ".vtp") return write_vtp(path, tmp, pd);
    int ok = 0;
    if (ext == ".vtk") {
      ok = write_with<vtkPolyDataWriter>(tmp, pd, [](vtkPolyDataWriter* w) { w->SetFileTypeToBinary(); });
    } else if (ext == ".stl") {
      ok = write_with<vtkSTLWriter>(tmp, pd, [](vtkSTLWriter* w) { w->SetFileTypeToBinary(); });
    } else if (ext == ".ply") {
      ok = write_with<vtkPLYWriter>(tmp, pd, [](vtkPLYWriter* w) { w->SetFileTypeToBinary(); });
    } else {
      ok = write_with<vtkOBJWriter>(tmp, pd, [](vtkOBJWriter*) {});
    }
    if (ok != 1) throw Error(path.string() + ": VTK could not write the file");
  });
}

}  // namespace

void write_mesh(const fs::path& path, const TriMesh& mesh, const MatX3* positions,
                const std::vector<NamedArray>& extra) {
  mesh_write_extension(path);  // before any work
  write_polydata(path, mesh_polydata(path, mesh, positions, extra));
}

std::vector<std::string> parse_mesh_copies(const std::optional<std::string>& value) {
  std::vector<std::string> formats;
  if (!value) return formats;
  std::stringstream items(*value);
  for (std::string f; std::getline(items, f, ',');) {
    if (std::find(kMeshCopyFormats.begin(), kMeshCopyFormats.end(), f) == kMeshCopyFormats.end())
      throw InputError("--mesh-copies: expected formats from vtk|stl|ply|obj, found \"" + f + "\"");
    if (std::find(formats.begin(), formats.end(), f) == formats.end()) formats.push_back(f);
  }
  if (formats.empty()) throw InputError("--mesh-copies: expected formats from vtk|stl|ply|obj, found \"\"");
  return formats;
}

void write_mesh_copies(const fs::path& path, const std::vector<std::string>& formats, const TriMesh& mesh,
                       const MatX3* positions, const std::vector<NamedArray>& extra) {
  if (formats.empty()) return;
  const vtkSmartPointer<vtkPolyData> pd = mesh_polydata(path, mesh, positions, extra);
  for (const auto& format : formats) {
    fs::path copy = path;
    write_polydata(copy.replace_extension("." + format), pd);
  }
}

void write_lines(const fs::path& path, const MatX3& x, const std::vector<std::pair<int, int>>& lines,
                 const std::vector<NamedArray>& arrays) {
  if (lower_extension(path) != ".vtp") throw_input_error(path.string(), "extension", ".vtp", "\"" + lower_extension(path) + "\"");
  if (!x.allFinite()) throw NumericalError(path.string() + ": refusing to write non-finite coordinates");
  vtkNew<vtkPolyData> pd;
  set_points(pd, x);
  vtkNew<vtkCellArray> cells;
  for (const auto& [a, b] : lines) {
    const vtkIdType ids[2] = {a, b};
    cells->InsertNextCell(2, ids);
  }
  pd->SetLines(cells);
  add_named_arrays(pd, arrays, static_cast<Eigen::Index>(lines.size()), "write_lines");
  write_via_temp(path, [&](const fs::path& tmp) { write_vtp(path, tmp, pd); });
}

void write_pvd(const fs::path& path, const std::vector<std::string>& files, const std::vector<double>& times) {
  std::ostringstream s;
  s << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
  s.precision(12);
  for (size_t i = 0; i < files.size(); ++i)
    s << "    <DataSet timestep=\"" << times[i] << "\" file=\"" << files[i] << "\"/>\n";
  s << "  </Collection>\n</VTKFile>\n";
  write_file_atomic(path, s.str());
}

}  // namespace valve
