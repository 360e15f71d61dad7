// One request for any analytic mesh: each kind gets its own sizes, the others are ignored.
#include <catch2/catch.hpp>
#include <cmath>

#include "valve/mesh/analytic_mesh.hpp"

using namespace valve;

namespace {
double max_radius(const TriMesh& m) { return m.points.leftCols(2).rowwise().norm().maxCoeff(); }
}  // namespace

TEST_CASE("analytic mesh: each kind takes its own sizes", "[mesh][generators]") {
  AnalyticMeshRequest r;
  r.kind = "square_patch";
  r.side = 10;
  r.diameter = 99;  // not the square's
  const TriMesh square = generate_analytic_mesh(r, 1);
  CHECK(square.points.col(0).maxCoeff() - square.points.col(0).minCoeff() == Approx(10));
  CHECK(analytic_mesh_parameters(r) == nlohmann::json{{"side_mm", 10.0}});

  r.kind = "clamped_disk";
  r.diameter = 12;
  r.triangles = 200;
  CHECK(max_radius(generate_analytic_mesh(r, 1)) == Approx(6).epsilon(1e-6));

  // A leaflet on the cylinder of the given circumference: radius C / 2π.
  r.kind = "aortic_leaflet";
  r.diameter = 20;
  r.circumference = 90;
  r.triangles = 221;
  CHECK(max_radius(generate_analytic_mesh(r, 1)) == Approx(90 / (2 * M_PI)).epsilon(1e-6));
  CHECK(analytic_mesh_parameters(r)["circumference_mm"] == 90.0);

  // Three leaflets wrap a cylinder of three diameters, whatever circumference is asked.
  r.kind = "three_leaflet_valve";
  r.triangles = 300;
  const TriMesh valve = generate_analytic_mesh(r, 1);
  CHECK(max_radius(valve) == Approx(60 / (2 * M_PI)).epsilon(1e-6));
  CHECK(analytic_mesh_parameters(r)["circumference_mm"] == 60.0);
  CHECK(r.is_valve());
  int first_leaflet = 0;
  for (int l : valve.leaflet) first_leaflet += l == 0;
  CHECK(first_leaflet == Approx(100).margin(10));  // a third of the triangles each
}

TEST_CASE("analytic mesh: a graft scales one aortic leaflet, seeds vary the mesh", "[mesh][generators]") {
  AnalyticMeshRequest r;
  r.kind = "aortic_valve";
  r.triangles = 300;
  r.graft_leaflet = 1;
  r.graft_height_pct = 40;
  const nlohmann::json p = analytic_mesh_parameters(r);
  CHECK(p["graft_leaflet"] == 1);
  CHECK(p["graft_height_pct"] == 40.0);
  CHECK(p["gamma_deg"] == 22.0);
  const TriMesh graft = generate_analytic_mesh(r, 1);
  // The taller graft reaches higher up its commissures than the native leaflet 0 reaches.
  auto height = [&](int leaflet) {
    double lo = 1e9, hi = -1e9;
    for (int t = 0; t < graft.num_triangles(); ++t)
      if (graft.leaflet[t] == leaflet)
        for (int k = 0; k < 3; ++k) lo = std::min(lo, graft.points(graft.triangles[t][k], 2)), hi = std::max(hi, graft.points(graft.triangles[t][k], 2));
    return hi - lo;
  };
  CHECK(height(1) > 1.2 * height(0));
  // The gap between the graft's sides and its neighbours' commissures reaches the generator.
  CHECK(p["graft_commissure_gap_mm"] == 0.3);
  auto widest_start_angle = [](const TriMesh& m, int leaflet) {
    double widest = 0;
    for (int t = 0; t < m.num_triangles(); ++t)
      if (m.leaflet[t] == leaflet)
        for (int k = 0; k < 3; ++k) {
          const Vec3 p = m.initial.row(m.triangles[t][k]);
          // Leaflet 1 is centred on 120°: angles from its midline.
          const double pi = std::acos(-1.0);
          widest = std::max(widest, std::abs(std::remainder(std::atan2(p.y(), p.x()) - 2 * pi / 3, 2 * pi)));
        }
    return widest;
  };
  r.graft_commissure_gap = 0.5;
  CHECK(analytic_mesh_parameters(r)["graft_commissure_gap_mm"] == 0.5);
  CHECK(widest_start_angle(generate_analytic_mesh(r, 1), 1) == Approx(1.047 - 0.5 / 10).epsilon(1e-9));

  r.kind = "square_patch";
  CHECK_FALSE(r.has_leaflets());
  const TriMesh a = generate_analytic_mesh(r, 1), b = generate_analytic_mesh(r, 1), c = generate_analytic_mesh(r, 2);
  CHECK(a.points == b.points);
  CHECK_FALSE((c.points.rows() == a.points.rows() && c.points == a.points));
}
