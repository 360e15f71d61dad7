#include "valve/mesh/analytic_mesh.hpp"

namespace valve {

namespace {
// Every generator's options take the fiber angle and the planar mesher's settings alike.
template <class Options>
Options with_fibers_and_mesh(Options o, const AnalyticMeshRequest& r, const PlanarMeshOptions& mesh) {
  o.fiber_angle_deg = r.fiber_angle_deg;
  o.mesh = mesh;
  return o;
}
}  // namespace

TriMesh generate_analytic_mesh(const AnalyticMeshRequest& r, std::uint64_t seed) {
  PlanarMeshOptions mesh{r.triangles / (r.is_valve() ? 3 : 1), seed};
  mesh.jitter = r.jitter;
  mesh.max_iterations = r.relax_iterations;
  if (r.kind == "square_patch") {
    SquarePatchOptions o;
    o.side = r.side;
    return generate_square_patch(with_fibers_and_mesh(o, r, mesh));
  }
  if (r.kind == "clamped_disk") {
    DiskOptions o;
    o.diameter = r.diameter;
    return generate_clamped_disk(with_fibers_and_mesh(o, r, mesh));
  }
  if (r.kind == "aortic_valve") {
    AorticValveOptions o;
    o.diameter = r.diameter;
    o.gamma_deg = r.gamma_deg;
    o.commissure_height = r.commissure_height;
    o.width_scale[r.graft_leaflet] = 1 + r.graft_width_pct / 100;
    o.height_scale[r.graft_leaflet] = 1 + r.graft_height_pct / 100;
    o.graft_commissure_gap = r.graft_commissure_gap;
    return generate_aortic_valve(with_fibers_and_mesh(o, r, mesh));
  }
  LeafletOptions o;
  o.diameter = r.diameter;
  o.cylinder_circumference = r.circumference;
  o = with_fibers_and_mesh(o, r, mesh);
  return r.kind == "aortic_leaflet" ? generate_aortic_leaflet(o) : generate_three_leaflet_valve(o);
}

nlohmann::json analytic_mesh_parameters(const AnalyticMeshRequest& r) {
  if (r.kind == "square_patch") return {{"side_mm", r.side}};
  if (r.kind == "clamped_disk") return {{"diameter_mm", r.diameter}};
  if (r.kind == "aortic_valve")
    return {{"diameter_mm", r.diameter}, {"gamma_deg", r.gamma_deg}, {"commissure_height_mm", r.commissure_height},
            {"graft_leaflet", r.graft_leaflet}, {"graft_width_pct", r.graft_width_pct}, {"graft_height_pct", r.graft_height_pct},
            {"graft_commissure_gap_mm", r.graft_commissure_gap}};
  return {{"diameter_mm", r.diameter},
          {"circumference_mm", r.kind == "aortic_leaflet" ? r.circumference : 3 * r.diameter}};
}

}  // namespace valve
