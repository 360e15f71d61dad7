#include "valve/imaging/triangulation.hpp"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkCleanPolyData.h>
#include <vtkDiscreteFlyingEdges3D.h>
#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkPolyDataConnectivityFilter.h>
#include <vtkPolyDataNormals.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWindowedSincPolyDataFilter.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>

#include "valve/core/error.hpp"

namespace valve {

TriMesh triangulate_labels(const LabelMap& map, const TriangulationOptions& o, TriangulationSummary* summary) {
  if (o.labels.empty()) throw_input_error("triangulation", "labels", "at least one label", "none");
  if (o.smoothing_iterations < 0 || o.smoothing_iterations > 1000)
    throw_input_error("triangulation", "smoothing_iterations", "0..1000", std::to_string(o.smoothing_iterations));
  if (!(o.pass_band > 0 && o.pass_band < 2)) throw_input_error("triangulation", "pass_band", "a value in (0, 2)", std::to_string(o.pass_band));
  const ImageGeometry& g = map.geometry;
  std::size_t hits = 0;
  for (std::uint8_t l : map.labels) hits += std::find(o.labels.begin(), o.labels.end(), int(l)) != o.labels.end();
  if (hits == 0) throw_input_error("triangulation", "labels", "voxels carrying the requested label(s)", "none in the label map");

  // Index-space image (spacing applied, origin and direction later), padded by one voxel of
  // background so that surfaces touching the image border still close.
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(g.size[0] + 2, g.size[1] + 2, g.size[2] + 2);
  image->SetSpacing(g.spacing.x(), g.spacing.y(), g.spacing.z());
  image->SetOrigin(-g.spacing.x(), -g.spacing.y(), -g.spacing.z());
  auto scalars = vtkSmartPointer<vtkUnsignedCharArray>::New();
  scalars->SetNumberOfTuples(vtkIdType(g.size[0] + 2) * (g.size[1] + 2) * (g.size[2] + 2));
  scalars->Fill(0);
  for (int k = 0; k < g.size[2]; ++k)
    for (int j = 0; j < g.size[1]; ++j)
      for (int i = 0; i < g.size[0]; ++i) {
        const vtkIdType padded = (i + 1) + vtkIdType(g.size[0] + 2) * ((j + 1) + vtkIdType(g.size[1] + 2) * (k + 1));
        scalars->SetValue(padded, map.labels[g.linear_index(i, j, k)]);
      }
  image->GetPointData()->SetScalars(scalars);

  auto contour = vtkSmartPointer<vtkDiscreteFlyingEdges3D>::New();
  contour->SetInputData(image);
  for (std::size_t k = 0; k < o.labels.size(); ++k) contour->SetValue(static_cast<int>(k), o.labels[k]);
  contour->ComputeNormalsOff();
  contour->ComputeGradientsOff();
  contour->ComputeScalarsOff();
  auto clean = vtkSmartPointer<vtkCleanPolyData>::New();
  clean->SetInputConnection(contour->GetOutputPort());
  vtkAlgorithmOutput* last = clean->GetOutputPort();
  auto smooth = vtkSmartPointer<vtkWindowedSincPolyDataFilter>::New();
  if (o.smoothing_iterations > 0) {
    smooth->SetInputConnection(last);
    smooth->SetNumberOfIterations(o.smoothing_iterations);
    smooth->SetPassBand(o.pass_band);
    smooth->BoundarySmoothingOff();
    smooth->FeatureEdgeSmoothingOff();
    smooth->NonManifoldSmoothingOn();
    smooth->NormalizeCoordinatesOn();
    last = smooth->GetOutputPort();
  }
  auto connectivity = vtkSmartPointer<vtkPolyDataConnectivityFilter>::New();
  connectivity->SetInputConnection(last);
  connectivity->SetExtractionModeToAllRegions();
  connectivity->Update();
  const int regions = connectivity->GetNumberOfExtractedRegions();
  if (o.largest_only) {
    connectivity->SetExtractionModeToLargestRegion();
    auto clean_again = vtkSmartPointer<vtkCleanPolyData>::New();  // drops the points of the other regions
    clean_again->SetInputConnection(connectivity->GetOutputPort());
    last = clean_again->GetOutputPort();
    clean_again->Update();
  }
  // Consistent, outward-pointing triangle winding.
  auto normals = vtkSmartPointer<vtkPolyDataNormals>::New();
  normals->SetInputConnection(last);
  normals->ConsistencyOn();
  normals->AutoOrientNormalsOn();
  normals->SplittingOff();
  normals->ComputeCellNormalsOff();
  normals->Update();
  vtkPolyData* surface = normals->GetOutput();

  TriMesh mesh;
  mesh.points.resize(surface->GetNumberOfPoints(), 3);
  for (vtkIdType p = 0; p < surface->GetNumberOfPoints(); ++p) {
    double x[3];
    surface->GetPoint(p, x);
    mesh.points.row(p) = (g.origin + g.direction * Vec3(x[0], x[1], x[2])).transpose();
  }
  vtkCellArray* polys = surface->GetPolys();
  auto it = vtk::TakeSmartPointer(polys->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell()) {
    vtkIdType n;
    const vtkIdType* ids;
    it->GetCurrentCell(n, ids);
    if (n == 3) mesh.triangles.emplace_back(int(ids[0]), int(ids[1]), int(ids[2]));
  }
  // A left-handed direction matrix mirrors the surface: restore outward winding.
  if (g.direction.determinant() < 0)
    for (Tri& t : mesh.triangles) std::swap(t[1], t[2]);
  mesh.fill_defaults();

  if (summary) {
    summary->regions = regions;
    summary->area_mm2 = 0;
    summary->enclosed_volume_mm3 = 0;
    for (const Tri& t : mesh.triangles) {
      const Vec3 a = mesh.points.row(t[0]), b = mesh.points.row(t[1]), c = mesh.points.row(t[2]);
      summary->area_mm2 += 0.5 * (b - a).cross(c - a).norm();
      summary->enclosed_volume_mm3 += a.dot(b.cross(c)) / 6;
    }
  }
  return mesh;
}

}  // namespace valve
