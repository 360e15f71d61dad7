#include "valve/scene/closure_files.hpp"

#include <algorithm>

#include "valve/chordae/slicer_markups.hpp"
#include "valve/core/atomic_file.hpp"
#include "valve/core/error.hpp"
#include "valve/io/mesh_io.hpp"
#include "valve/mesh/validate.hpp"

namespace valve {
namespace fs = std::filesystem;

TriMesh read_leaflet_mesh(const fs::path& path) {
  std::vector<NamedArray> arrays;
  TriMesh mesh = read_mesh(path, &arrays);
  validate_mesh(mesh, path.string());
  if (std::none_of(arrays.begin(), arrays.end(), [](const NamedArray& a) { return a.per_cell && a.name == "FiberDirection"; }))
    throw_input_error(path.string(), "FiberDirection", "a cell array of fiber directions (the leaflet laws are anisotropic)", "none");
  return mesh;
}

void remove_closure_files(const fs::path& out) {
  std::error_code ec;
  for (const char* name : {"closed.sim.vtp", "closed.sim.pvd", "closed.chordae.vtp", "coaptation_columns.csv",
                           "closed.landmarks.mrk.json"})
    fs::remove(out / name, ec);
  for (const auto& format : kMeshCopyFormats) fs::remove(out / ("closed.sim." + format), ec);
  if (fs::is_directory(out / "series", ec))
    for (const auto& e : fs::directory_iterator(out / "series", ec))
      if (e.path().filename().string().rfind("step_", 0) == 0 && e.path().extension() == ".vtp") fs::remove(e.path(), ec);
}

ClosureTimeSeries::ClosureTimeSeries(fs::path out, const TriMesh& mesh, bool enabled, int every)
    : out_(std::move(out)), mesh_(mesh), enabled_(enabled), every_(every) {}

void ClosureTimeSeries::step(const MatX3& positions, double t) {
  ++steps_;
  if (!enabled_ || steps_ % every_ != 0) return;
  const std::string name = "series/step_" + std::to_string(steps_) + ".vtp";
  write_mesh(out_ / name, mesh_, &positions);
  files_.push_back(name);
  times_.push_back(t);
}

void ClosureTimeSeries::finish() const {
  if (enabled_) write_pvd(out_ / "closed.sim.pvd", files_, times_);
}

void write_closed_valve_files(const fs::path& out, const TriMesh& mesh, const VecX& x, const ClosedValveAnalysis& analysis,
                              const std::vector<std::string>& mesh_copies) {
  const MatX3 pos = unflatten(x);
  write_mesh(out / "closed.sim.vtp", mesh, &pos, analysis.arrays);
  write_mesh_copies(out / "closed.sim.vtp", mesh_copies, mesh, &pos, analysis.arrays);
  if (analysis.coaptation) write_file_atomic(out / "coaptation_columns.csv", coaptation_columns_csv(*analysis.coaptation));
  const std::vector<int>* coapting = analysis.coaptation ? &analysis.coaptation->coapting : nullptr;
  write_slicer_curves(out / "closed.landmarks.mrk.json", valve_landmark_curves(mesh, x, coapting));
}

}  // namespace valve
