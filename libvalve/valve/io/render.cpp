#include "valve/io/render.hpp"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkLookupTable.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkSmartPointer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkWindowToImageFilter.h>
#include <vtkXMLPolyDataReader.h>

#include <cstdlib>

#include "valve/core/atomic_file.hpp"
#include "valve/core/error.hpp"

namespace valve {
namespace fs = std::filesystem;

bool render_display_available() {
  const char* d = std::getenv("DISPLAY");
  return d && *d;
}

std::vector<fs::path> render_views(const fs::path& mesh_file, const RenderOptions& opt, const fs::path& out_dir,
                                   const std::string& stem) {
  const std::string file = mesh_file.string();
  if (!fs::exists(mesh_file)) throw InputError(file + ": expected an existing .vtp file, found nothing");
  auto reader = vtkSmartPointer<vtkXMLPolyDataReader>::New();
  reader->SetFileName(file.c_str());
  reader->Update();
  vtkPolyData* pd = reader->GetOutput();
  if (!pd || pd->GetNumberOfPoints() == 0) throw InputError(file + ": expected a polygon mesh, found no points");
  int axis = opt.axis == "x" ? 0 : opt.axis == "y" ? 1 : opt.axis == "z" ? 2 : -1;
  if (axis < 0) throw InputError("render axis: expected x, y or z, found \"" + opt.axis + "\"");

  auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  mapper->SetInputData(pd);
  auto lut = vtkSmartPointer<vtkLookupTable>::New();
  if (!opt.array.empty()) {
    vtkDataArray* a = pd->GetPointData()->GetArray(opt.array.c_str());
    if (!a) throw InputError(file + ": point array \"" + opt.array + "\": expected in the mesh, found none");
    double range[2] = {opt.range_min, opt.range_max};
    // Vectors (Displacement) are coloured by their magnitude.
    const int component = a->GetNumberOfComponents() == 1 ? 0 : -1;
    if (!(opt.range_max > opt.range_min)) a->GetRange(range, component);
    if (!(range[1] > range[0])) range[1] = range[0] + 1;
    lut->SetRange(range);
    lut->SetHueRange(0.0, 0.667);  // red (touching) to blue (far)
    lut->SetVectorModeToMagnitude();
    if (opt.below_range_grey) {
      lut->SetBelowRangeColor(0.75, 0.75, 0.75, 1);
      lut->UseBelowRangeColorOn();
    }
    lut->Build();
    mapper->SetLookupTable(lut);
    mapper->SetScalarModeToUsePointFieldData();
    mapper->SelectColorArray(opt.array.c_str());
    mapper->SetScalarRange(range);
    mapper->ScalarVisibilityOn();
  } else {
    mapper->ScalarVisibilityOff();
  }
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  // Edges show the mesh a simulation runs on; on a dense scan surface they would paint it black.
  if (pd->GetNumberOfCells() <= opt.max_cells_with_edges) actor->GetProperty()->EdgeVisibilityOn();
  if (opt.array.empty()) actor->GetProperty()->SetColor(0.93, 0.80, 0.70);  // tissue
  actor->GetProperty()->SetEdgeColor(0.2, 0.2, 0.2);
  actor->GetProperty()->SetLineWidth(0.5);

  auto renderer = vtkSmartPointer<vtkRenderer>::New();
  renderer->AddActor(actor);
  renderer->SetBackground(1, 1, 1);
  if (!opt.array.empty()) {
    auto bar = vtkSmartPointer<vtkScalarBarActor>::New();
    bar->SetLookupTable(lut);
    bar->SetTitle(opt.array.c_str());
    bar->SetNumberOfLabels(5);
    bar->GetTitleTextProperty()->SetColor(0, 0, 0);
    bar->GetLabelTextProperty()->SetColor(0, 0, 0);
    bar->SetWidth(0.12);
    renderer->AddActor2D(bar);
  }
  auto title = vtkSmartPointer<vtkTextActor>::New();
  title->SetInput((opt.title.empty() ? opt.array : opt.title).c_str());
  title->GetTextProperty()->SetColor(0, 0, 0);
  title->GetTextProperty()->SetFontSize(20);
  title->SetDisplayPosition(10, opt.height - 30);
  renderer->AddActor2D(title);

  auto window = vtkSmartPointer<vtkRenderWindow>::New();
  window->SetOffScreenRendering(1);
  window->AddRenderer(renderer);
  window->SetSize(opt.width, opt.height);

  std::vector<fs::path> written;
  fs::create_directories(out_dir);
  for (const std::string& view : opt.views) {
    double bounds[6];
    pd->GetBounds(bounds);
    const double centre[3] = {(bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2, (bounds[4] + bounds[5]) / 2};
    double dir[3] = {0, 0, 0}, up[3] = {0, 0, 0};
    if (view == "top") {
      dir[axis] = 1;            // camera on the +axis side looking down the axis
      up[(axis + 1) % 3] = 1;
    } else if (view == "side") {
      dir[(axis + 1) % 3] = 1;  // camera beside the valve
      up[axis] = 1;
    } else {
      throw InputError("render view: expected top or side, found \"" + view + "\"");
    }
    vtkCamera* cam = renderer->GetActiveCamera();
    cam->SetFocalPoint(centre);
    cam->SetPosition(centre[0] + dir[0], centre[1] + dir[1], centre[2] + dir[2]);
    cam->SetViewUp(up);
    renderer->ResetCamera();
    window->Render();
    auto grab = vtkSmartPointer<vtkWindowToImageFilter>::New();
    grab->SetInput(window);
    grab->ReadFrontBufferOff();
    grab->Update();
    const fs::path target = out_dir / (stem + "_" + view + ".png");
    write_via_temp(target, [&](const fs::path& tmp) {
      auto png = vtkSmartPointer<vtkPNGWriter>::New();
      png->SetFileName(tmp.string().c_str());
      png->SetInputConnection(grab->GetOutputPort());
      png->Write();
      if (png->GetErrorCode() != 0) throw Error(target.string() + ": PNG write failed");
    });
    written.push_back(target);
  }
  return written;
}

}  // namespace valve
