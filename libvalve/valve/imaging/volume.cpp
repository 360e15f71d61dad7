#include "valve/imaging/volume.hpp"

#include <cmath>

#include "valve/core/error.hpp"

namespace valve {

ImageGeometry grid_covering(const Vec3& lo, const Vec3& hi, double spacing) {
  if (!(spacing > 0) || !(hi.array() > lo.array()).all())
    throw InputError("grid_covering: expected spacing > 0 and a box with hi > lo");
  ImageGeometry g;
  g.spacing = Vec3::Constant(spacing);
  g.origin = lo;
  for (int a = 0; a < 3; ++a) g.size[a] = static_cast<int>(std::ceil((hi[a] - lo[a]) / spacing)) + 1;
  return g;
}

}  // namespace valve
