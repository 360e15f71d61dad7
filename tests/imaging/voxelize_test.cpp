// Voxelization against analytic volumes: the partial-volume ramp is symmetric about the
// tissue boundary, so the summed occupancy × voxel volume approximates the object's volume
// to within the discretization error of a surface at 0.1-0.2 mm.
#include <catch2/catch.hpp>
#include <cmath>
#include <numeric>

#include "valve/imaging/voxelize.hpp"

using namespace valve;

namespace {
constexpr double pi = 3.14159265358979323846;

double tissue_volume(const Voxelizer& v) {
  const double voxel = v.geometry().spacing.prod();
  return voxel * std::accumulate(v.occupancy().begin(), v.occupancy().end(), 0.0);
}
}  // namespace

TEST_CASE("grid_covering spans the box in whole voxels", "[imaging][voxelize]") {
  const ImageGeometry g = grid_covering(Vec3(-1, -2, 0), Vec3(1, 2, 3), 0.5);
  CHECK(g.size[0] >= 4);
  CHECK(g.size[1] >= 8);
  CHECK(g.size[2] >= 6);
  const Vec3 first = g.physical_point(Vec3::Zero());
  const Vec3 last = g.physical_point(Vec3(g.size[0] - 1, g.size[1] - 1, g.size[2] - 1));
  CHECK(first.x() <= -1 + 0.25 + 1e-12);
  CHECK(last.z() >= 3 - 0.25 - 1e-12);
  const Vec3 back = g.continuous_index(g.physical_point(Vec3(1.5, 2, 3)));
  CHECK(back.isApprox(Vec3(1.5, 2, 3), 1e-12));
}

TEST_CASE("a flat sheet voxelizes to area × thickness", "[imaging][voxelize]") {
  // A 10 × 8 mm square of two triangles, 1 mm thick, tilted so that it cuts voxels obliquely.
  const double tilt = 0.3;
  MatX3 p(4, 3);
  p << 0, 0, 0, 10, 0, 10 * tilt, 10, 8, 10 * tilt, 0, 8, 0;
  const std::vector<Tri> tris{{0, 1, 2}, {0, 2, 3}};
  const double area = 10 * std::sqrt(1 + tilt * tilt) * 8;
  Voxelizer vox(grid_covering(Vec3(-2, -2, -2), Vec3(12, 10, 5), 0.2));
  vox.add_sheet(p, tris, 1.0);
  // Every point within t/2 of the mid-surface: the slab area × t plus, along the perimeter P,
  // a half-cylinder of radius t/2 (the rounded rim), P π t² / 8.
  const double perimeter = 2 * (10 * std::sqrt(1 + tilt * tilt) + 8);
  CHECK(tissue_volume(vox) == Approx(area * 1.0 + perimeter * pi / 8).epsilon(0.03));
  for (float f : vox.occupancy()) REQUIRE((f >= 0 && f <= 1));
}

TEST_CASE("tubes and an ellipsoid voxelize to their volumes", "[imaging][voxelize]") {
  SECTION("capsule: π r² L + 4/3 π r³") {
    Voxelizer vox(grid_covering(Vec3(-2, -2, -2), Vec3(12, 2, 2), 0.1));
    vox.add_tubes({{Vec3(0, 0, 0), Vec3(10, 0, 0)}}, 1.0);
    const double r = 0.5, expected = pi * r * r * 10 + 4.0 / 3 * pi * r * r * r;
    CHECK(tissue_volume(vox) == Approx(expected).epsilon(0.04));
  }
  SECTION("ellipsoid: 4/3 π a b c") {
    Voxelizer vox(grid_covering(Vec3(-5, -5, -7), Vec3(5, 5, 7), 0.2));
    vox.add_ellipsoid(Vec3::Zero(), Vec3(3, 3, 5));
    CHECK(tissue_volume(vox) == Approx(4.0 / 3 * pi * 3 * 3 * 5).epsilon(0.04));
  }
}

TEST_CASE("grey values and seeded noise", "[imaging][voxelize]") {
  Voxelizer vox(grid_covering(Vec3(0, 0, 0), Vec3(8, 8, 8), 0.25));
  Volume v = vox.to_volume(-100, 900);  // no tissue: all background
  for (float x : v.values) REQUIRE(x == -100);
  Volume a = v, b = v;
  add_gaussian_noise(a, 40, 7);
  add_gaussian_noise(b, 40, 7);
  CHECK(a.values == b.values);  // reproducible
  double mean = 0, sq = 0;
  for (float x : a.values) mean += x;
  mean /= a.values.size();
  for (float x : a.values) sq += (x - mean) * (x - mean);
  const double sd = std::sqrt(sq / (a.values.size() - 1));
  // ~35,000 samples: the mean within 4 standard errors, the sd within 3 %.
  CHECK(std::abs(mean + 100) < 4 * 40 / std::sqrt(double(a.values.size())));
  CHECK(sd == Approx(40).epsilon(0.03));
  add_gaussian_noise(b, 40, 8);
  CHECK(a.values != b.values);
}
