#pragma once
// PNG pictures of a mesh for people: top and side views coloured by a point array,
// rendered offscreen with VTK. Debian's VTK renders through X only, so a caller without
// a display runs under xvfb-run (the valve-render stage does that itself).
#include <filesystem>
#include <string>
#include <vector>

namespace valve {

struct RenderOptions {
  std::string array;            // point array to colour by ("" = plain surface)
  double range_min = 0, range_max = 0;  // colour range; equal values: the array's range
  /// Values below range_min (e.g. the coaptation "no hit" sentinel) are drawn grey.
  bool below_range_grey = true;
  int width = 900, height = 900;
  std::vector<std::string> views{"top", "side"};  // top: along −axis, side: along +x
  std::string axis = "z";       // valve axis: x, y or z
  std::string title;            // drawn at the top left; the array name if empty
  int max_cells_with_edges = 20000;  // denser meshes are drawn without their edges
};

/// Whether this process can open an X display for rendering.
bool render_display_available();

/// Renders `mesh_file` (.vtp) once per view to out_dir/<stem>_<view>.png and returns the
/// files written. Throws InputError for an unknown array or view.
std::vector<std::filesystem::path> render_views(const std::filesystem::path& mesh_file, const RenderOptions& opt,
                                                const std::filesystem::path& out_dir, const std::string& stem);

}  // namespace valve
