#pragma once
// Nearest-neighbour queries over a fixed point set through nanoflann's k-d tree (Debian
// libnanoflann-dev): O(log n) per query instead of the O(n) scan of nearest_point_index, for
// the ICP's pairing and a comparison's node distances, which query every node of one mesh
// against every node of another (a 16,566-triangle scan against its reference: 8,000 x 8,000
// pairs per ICP iteration by brute force).
#include <memory>

#include "valve/core/types.hpp"

namespace valve {

class NearestPoints {
 public:
  /// Indexes the rows of `points`, which must outlive this object (it is not copied).
  explicit NearestPoints(const MatX3& points);
  ~NearestPoints();
  NearestPoints(const NearestPoints&) = delete;
  NearestPoints& operator=(const NearestPoints&) = delete;

  /// Index of the row nearest to p (the lowest index among equally near rows is not
  /// guaranteed; -1 when the set is empty), and its distance in `distance` when given.
  int nearest(const Vec3& p, double* distance = nullptr) const;

 private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
};

}  // namespace valve
