#include "valve/mesh/nearest_points.hpp"

#include <nanoflann.hpp>

#include <cmath>
#include <cstdint>
#include <limits>

namespace valve {

namespace {
// nanoflann's dataset interface over the rows of a MatX3.
struct MatrixRows {
  const MatX3& points;
  size_t kdtree_get_point_count() const { return static_cast<size_t>(points.rows()); }
  double kdtree_get_pt(size_t i, size_t dim) const { return points(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(dim)); }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;  // let nanoflann compute it
  }
};
using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, MatrixRows>, MatrixRows, 3, uint32_t>;
}  // namespace

struct NearestPoints::Tree {
  MatrixRows rows;
  KdTree index;
  // Leaves of up to 10 points: nanoflann's default, near the fastest for 3-D queries.
  explicit Tree(const MatX3& points) : rows{points}, index(3, rows, nanoflann::KDTreeSingleIndexAdaptorParams(10)) {}
};

NearestPoints::NearestPoints(const MatX3& points) {
  if (points.rows() > 0) tree_ = std::make_unique<Tree>(points);
}

NearestPoints::~NearestPoints() = default;

int NearestPoints::nearest(const Vec3& p, double* distance) const {
  if (!tree_) {
    if (distance) *distance = std::numeric_limits<double>::infinity();
    return -1;
  }
  uint32_t index = 0;
  double squared = 0;
  nanoflann::KNNResultSet<double, uint32_t> result(1);
  result.init(&index, &squared);
  const double query[3] = {p[0], p[1], p[2]};
  tree_->index.findNeighbors(result, query, nanoflann::SearchParams());
  if (distance) *distance = std::sqrt(squared);
  return static_cast<int>(index);
}

}  // namespace valve
