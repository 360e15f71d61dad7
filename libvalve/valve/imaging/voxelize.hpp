#pragma once
// Voxelization of surfaces, tubes and ellipsoids into a micro-CT-like volume.
//
// Each object adds its tissue occupancy f ∈ [0, 1] to the voxels near it, combined by the
// maximum. The occupancy is a partial-volume ramp on the signed distance to the object's
// surface, f = clamp(1/2 − (d − r)/w, 0, 1), with d the distance from the voxel centre to
// the object's core (mid-surface, centre line), r the half thickness (radius) and w the mean
// voxel spacing: a voxel cut in half by a planar tissue boundary gets f = 1/2.
// The grey value is background + (tissue − background) f; blur and noise are applied after.
#include <cstdint>
#include <utility>
#include <vector>

#include "valve/imaging/volume.hpp"
#include "valve/mesh/tri_mesh.hpp"

namespace valve {

/// Occupancy grid over `geometry`, initially empty.
class Voxelizer {
 public:
  explicit Voxelizer(const ImageGeometry& geometry);
  /// A sheet of the given thickness around the triangles of a mid-surface.
  void add_sheet(const MatX3& points, const std::vector<Tri>& triangles, double thickness);
  /// Cylinders with hemispherical caps (capsules) of the given diameter around segments.
  void add_tubes(const std::vector<std::pair<Vec3, Vec3>>& segments, double diameter);
  /// An axis-aligned ellipsoid (signed distance approximated radially).
  void add_ellipsoid(const Vec3& centre, const Vec3& semi_axes);
  const std::vector<float>& occupancy() const { return occupancy_; }
  const ImageGeometry& geometry() const { return geometry_; }
  /// Grey values background + (tissue − background) f.
  Volume to_volume(float background, float tissue) const;

 private:
  // Visits the voxels whose centres may lie within `margin` of the physical box [lo, hi].
  template <class F>
  void for_voxels_near(const Vec3& lo, const Vec3& hi, double margin, F&& visit);
  ImageGeometry geometry_;
  std::vector<float> occupancy_;
  double ramp_width_;
};

/// Adds zero-mean Gaussian noise of standard deviation sigma, seeded (written here rather
/// than through ITK's noise filters so that the result does not depend on the thread count).
void add_gaussian_noise(Volume& volume, double sigma, std::uint64_t seed);

}  // namespace valve
