#include "valve/imaging/voxelize.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "valve/core/error.hpp"
#include "valve/mesh/closest_point.hpp"

namespace valve {

Voxelizer::Voxelizer(const ImageGeometry& geometry)
    : geometry_(geometry), occupancy_(geometry.voxel_count(), 0.0f), ramp_width_(geometry.spacing.mean()) {}

template <class F>
void Voxelizer::for_voxels_near(const Vec3& lo, const Vec3& hi, double margin, F&& visit) {
  // The box's corners in continuous index space bound it there (the map is affine).
  Vec3 ilo = Vec3::Constant(1e300), ihi = Vec3::Constant(-1e300);
  for (int c = 0; c < 8; ++c) {
    const Vec3 corner((c & 1) ? hi.x() + margin : lo.x() - margin, (c & 2) ? hi.y() + margin : lo.y() - margin,
                      (c & 4) ? hi.z() + margin : lo.z() - margin);
    const Vec3 idx = geometry_.continuous_index(corner);
    ilo = ilo.cwiseMin(idx);
    ihi = ihi.cwiseMax(idx);
  }
  int from[3], to[3];
  for (int a = 0; a < 3; ++a) {
    from[a] = std::max(0, static_cast<int>(std::ceil(ilo[a])));
    to[a] = std::min(geometry_.size[a] - 1, static_cast<int>(std::floor(ihi[a])));
    if (from[a] > to[a]) return;
  }
  for (int k = from[2]; k <= to[2]; ++k)
    for (int j = from[1]; j <= to[1]; ++j)
      for (int i = from[0]; i <= to[0]; ++i) {
        const std::size_t v = geometry_.linear_index(i, j, k);
        if (occupancy_[v] >= 1.0f) continue;
        visit(v, geometry_.physical_point(Vec3(i, j, k)));
      }
}

void Voxelizer::add_sheet(const MatX3& points, const std::vector<Tri>& triangles, double thickness) {
  const double half = thickness / 2, margin = half + ramp_width_;
  for (const Tri& t : triangles) {
    const Vec3 a = points.row(t[0]), b = points.row(t[1]), c = points.row(t[2]);
    for_voxels_near(a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c), margin, [&](std::size_t v, const Vec3& p) {
      const double d = point_triangle_distance(p, a, b, c);
      const float f = static_cast<float>(std::clamp(0.5 - (d - half) / ramp_width_, 0.0, 1.0));
      occupancy_[v] = std::max(occupancy_[v], f);
    });
  }
}

void Voxelizer::add_tubes(const std::vector<std::pair<Vec3, Vec3>>& segments, double diameter) {
  const double radius = diameter / 2, margin = radius + ramp_width_;
  for (const auto& [a, b] : segments) {
    for_voxels_near(a.cwiseMin(b), a.cwiseMax(b), margin, [&](std::size_t v, const Vec3& p) {
      const double d = point_segment_distance(p, a, b);
      const float f = static_cast<float>(std::clamp(0.5 - (d - radius) / ramp_width_, 0.0, 1.0));
      occupancy_[v] = std::max(occupancy_[v], f);
    });
  }
}

void Voxelizer::add_ellipsoid(const Vec3& centre, const Vec3& semi_axes) {
  for_voxels_near(centre - semi_axes, centre + semi_axes, ramp_width_, [&](std::size_t v, const Vec3& p) {
    const Vec3 r = p - centre;
    const double q = r.cwiseQuotient(semi_axes).norm();
    // Radial signed distance: the surface point on the ray from the centre is r / q.
    const double sd = q > 1e-12 ? r.norm() * (1 - 1 / q) : -semi_axes.minCoeff();
    const float f = static_cast<float>(std::clamp(0.5 - sd / ramp_width_, 0.0, 1.0));
    occupancy_[v] = std::max(occupancy_[v], f);
  });
}

Volume Voxelizer::to_volume(float background, float tissue) const {
  Volume vol{geometry_, std::vector<float>(occupancy_.size())};
  for (std::size_t v = 0; v < occupancy_.size(); ++v) vol.values[v] = background + (tissue - background) * occupancy_[v];
  return vol;
}

void add_gaussian_noise(Volume& volume, double sigma, std::uint64_t seed) {
  if (!(sigma >= 0)) throw InputError("add_gaussian_noise: expected sigma >= 0");
  if (sigma == 0) return;
  std::mt19937_64 rng(seed);
  std::normal_distribution<float> noise(0.0f, static_cast<float>(sigma));
  for (float& x : volume.values) x += noise(rng);
}

}  // namespace valve
