#pragma once
// The files a closure reads (the leaflet mesh) and leaves in its output folder (valve-simulate):
//   closed.sim.vtp (+ copies in other formats)  the closed leaflets with the analysis arrays
//   closed.chordae.vtp                          the chordae at the end, with each segment's tension
//   coaptation_columns.csv                      several leaflets: the band's height down each column
//   closed.landmarks.mrk.json                   annulus ring, free edges, coaptation line (3D Slicer)
//   closed.sim.pvd + series/step_N.vtp          the time series, when asked for
// A run replaces all of an earlier run's files, whatever it ends with, so that none is left
// beside a summary it does not belong to.
#include <filesystem>
#include <string>
#include <vector>

#include "valve/mesh/tri_mesh.hpp"
#include "valve/scene/closure_report.hpp"

namespace valve {

/// The leaflet mesh a scene names, validated (mesh/validate.hpp). A mesh without the
/// FiberDirection cell array is refused: every leaflet law is anisotropic, and without it each
/// triangle's fiber would silently follow its first edge (TriMesh::fill_defaults).
TriMesh read_leaflet_mesh(const std::filesystem::path& path);

/// Removes every file an earlier closure wrote into `out` (the summary aside).
void remove_closure_files(const std::filesystem::path& out);

/// Writes every `every`-th accepted step's leaflet positions as series/step_N.vtp, and the
/// .pvd index that lists them.
class ClosureTimeSeries {
 public:
  ClosureTimeSeries(std::filesystem::path out, const TriMesh& mesh, bool enabled, int every);
  /// One accepted step at simulated time t (ms); `positions` are the leaflet nodes'.
  void step(const MatX3& positions, double t);
  /// Writes closed.sim.pvd when the series is enabled.
  void finish() const;
  long steps() const { return steps_; }

 private:
  std::filesystem::path out_;
  const TriMesh& mesh_;
  bool enabled_;
  int every_;
  long steps_ = 0;
  std::vector<std::string> files_;
  std::vector<double> times_;
};

/// The closed valve's files: the mesh with `analysis`'s arrays (and its copies in
/// `mesh_copies` formats), the coaptation columns when there are several leaflets, and the
/// landmark curves. `x` holds the leaflet nodes' closed positions.
void write_closed_valve_files(const std::filesystem::path& out, const TriMesh& mesh, const VecX& x,
                              const ClosedValveAnalysis& analysis, const std::vector<std::string>& mesh_copies);

}  // namespace valve
