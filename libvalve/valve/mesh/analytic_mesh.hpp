#pragma once
// One request for any of the analytic meshes of generators.hpp, as valve-generate takes it:
// the kind, the triangle count of the whole mesh and each kind's sizes. Sizes a kind does
// not use are ignored.
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "valve/mesh/generators.hpp"
#include "valve/mesh/tri_mesh.hpp"

namespace valve {

struct AnalyticMeshRequest {
  std::string kind = "square_patch";  ///< square_patch, clamped_disk, aortic_leaflet, three_leaflet_valve, aortic_valve
  int triangles = 229;  ///< of the whole mesh; a valve's leaflets take a third each
  double fiber_angle_deg = 0;
  double jitter = 0;  ///< interior nodes moved by up to this many spacings (slivers for stability tests)
  int relax_iterations = PlanarMeshOptions{}.max_iterations;
  double side = 15;  ///< mm, square_patch
  double diameter = 20;  ///< mm, every other kind
  double circumference = 60;  ///< mm, the cylinder of aortic_leaflet
  double gamma_deg = 22, commissure_height = 5;  ///< aortic_valve
  int graft_leaflet = 0;  ///< aortic_valve: the leaflet scaled by the graft percentages
  double graft_width_pct = 0, graft_height_pct = 0;  ///< added to 100 % of its width and height
  double graft_commissure_gap = AorticValveOptions{}.graft_commissure_gap;  ///< mm, see AorticValveOptions

  /// A valve of three leaflets (three_leaflet_valve or aortic_valve).
  bool is_valve() const { return kind == "three_leaflet_valve" || kind == "aortic_valve"; }
  /// A kind with leaflets (every kind but the flat square and disk).
  bool has_leaflets() const { return kind != "square_patch" && kind != "clamped_disk"; }
};

/// The mesh of `request` with this random seed of the planar mesher.
TriMesh generate_analytic_mesh(const AnalyticMeshRequest& request, std::uint64_t seed);

/// The sizes of the request's kind, as the summary's parameters name them in mm and degrees
/// (three_leaflet_valve's circumference is its own, 3 diameters, whatever was asked).
nlohmann::json analytic_mesh_parameters(const AnalyticMeshRequest& request);

}  // namespace valve
