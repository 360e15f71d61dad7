#pragma once
// Triangle quality q = 4√3 a / (s1² + s2² + s3²) (seed 3.2.2.1): 1 for an equilateral
// triangle, 0 for a degenerate one.
#include <vector>

#include "valve/mesh/tri_mesh.hpp"

namespace valve {

double triangle_quality(const Vec3& a, const Vec3& b, const Vec3& c);
std::vector<double> triangle_qualities(const MatX3& x, const std::vector<Tri>& triangles);

struct QualitySummary {
  double mean = 0, min = 0, max = 0;
  int below_0_6 = 0;  // count of triangles under the usual FE accuracy threshold
};
QualitySummary summarize_quality(const std::vector<double>& q);

}  // namespace valve
