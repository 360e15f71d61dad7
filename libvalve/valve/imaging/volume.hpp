#pragma once
// A 3-D image on a physical grid, kept free of ITK and VTK types so that voxelization,
// phantoms and their tests compile against Eigen only. Voxel (i, j, k) sits at the physical
// point origin + direction · diag(spacing) · (i, j, k) (LPS, mm), as in ITK and NRRD.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "valve/core/types.hpp"

namespace valve {

struct ImageGeometry {
  std::array<int, 3> size{0, 0, 0};
  Vec3 spacing = Vec3::Ones();     // mm
  Vec3 origin = Vec3::Zero();      // mm, physical point of voxel (0, 0, 0)
  Mat3 direction = Mat3::Identity();  // columns: physical directions of the index axes

  std::size_t voxel_count() const { return std::size_t(size[0]) * size[1] * size[2]; }
  std::size_t linear_index(int i, int j, int k) const { return std::size_t(i) + std::size_t(size[0]) * (j + std::size_t(size[1]) * k); }
  Vec3 physical_point(const Vec3& continuous_index) const {
    return origin + direction * spacing.cwiseProduct(continuous_index);
  }
  Vec3 continuous_index(const Vec3& physical) const {
    return (direction.transpose() * (physical - origin)).cwiseQuotient(spacing);
  }
};

/// Grey values (any modality; phantoms use 0 for air and 1000 for tissue).
struct Volume {
  ImageGeometry geometry;
  std::vector<float> values;
};

/// Label map: 0 background, then the labels below.
struct LabelMap {
  ImageGeometry geometry;
  std::vector<std::uint8_t> labels;
};

enum TissueLabel : std::uint8_t { label_background = 0, label_leaflet = 1, label_chordae = 2, label_other_tissue = 3 };

/// An axis-aligned grid covering [lo, hi] (physical, mm) with the given isotropic spacing
/// and identity direction; the box is widened to whole voxels.
ImageGeometry grid_covering(const Vec3& lo, const Vec3& hi, double spacing);

}  // namespace valve
