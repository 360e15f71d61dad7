// Thinning against shapes whose skeletons are known: a tube is a curve, a Y of tubes has one
// junction and three ends, and the simple-point test on textbook neighbourhoods.
#include <catch2/catch.hpp>
#include <cmath>

#include "valve/imaging/skeleton.hpp"

using namespace valve;

namespace {

ImageGeometry grid(int nx, int ny, int nz) {
  ImageGeometry g;
  g.size = {nx, ny, nz};
  return g;
}

// Voxels within `radius` of the segment a-b (index units).
void add_tube(const ImageGeometry& g, std::vector<std::uint8_t>& mask, const Vec3& a, const Vec3& b, double radius) {
  for (int k = 0; k < g.size[2]; ++k)
    for (int j = 0; j < g.size[1]; ++j)
      for (int i = 0; i < g.size[0]; ++i) {
        const Vec3 p(i, j, k), d = b - a;
        const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
        if ((a + t * d - p).norm() <= radius) mask[g.linear_index(i, j, k)] = 1;
      }
}

struct Census {
  long voxels = 0;
  int ends = 0, junction_voxels = 0, isolated = 0;
};

Census census(const ImageGeometry& g, const std::vector<std::uint8_t>& s) {
  Census c;
  for (int k = 0; k < g.size[2]; ++k)
    for (int j = 0; j < g.size[1]; ++j)
      for (int i = 0; i < g.size[0]; ++i) {
        if (!s[g.linear_index(i, j, k)]) continue;
        ++c.voxels;
        int n = 0;
        for (int dz = -1; dz <= 1; ++dz)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
              const int x = i + dx, y = j + dy, z = k + dz;
              if ((dx || dy || dz) && x >= 0 && y >= 0 && z >= 0 && x < g.size[0] && y < g.size[1] && z < g.size[2])
                n += s[g.linear_index(x, y, z)];
            }
        c.ends += n == 1;
        c.junction_voxels += n >= 3;
        c.isolated += n == 0;
      }
  return c;
}

}  // namespace

TEST_CASE("simple points: textbook neighbourhoods", "[imaging][skeleton]") {
  std::uint8_t cube[27] = {};
  CHECK_FALSE(is_simple_point(cube));  // isolated: removing it deletes a component
  cube[12] = 1;                        // one face neighbour (-x): a curve end, simple
  CHECK(is_simple_point(cube));
  cube[14] = 1;  // and +x: the middle of a line, removing it cuts the line
  CHECK_FALSE(is_simple_point(cube));
  std::uint8_t full[27];
  for (auto& v : full) v = 1;
  CHECK_FALSE(is_simple_point(full));  // interior: removing it makes a cavity
  std::uint8_t half[27] = {};
  for (int n = 0; n < 27; ++n) half[n] = n / 9 <= 1;  // z <= centre: a flat face
  CHECK(is_simple_point(half));
}

TEST_CASE("a tube thins to one curve of its length", "[imaging][skeleton]") {
  const ImageGeometry g = grid(40, 11, 11);
  std::vector<std::uint8_t> mask(g.voxel_count(), 0);
  add_tube(g, mask, Vec3(5, 5, 5), Vec3(34, 5, 5), 2.5);
  const Census c = census(g, curve_skeleton(g, mask));
  CHECK(c.ends == 2);
  CHECK(c.junction_voxels == 0);
  CHECK(c.isolated == 0);
  // The axis is 30 voxels long; thinning keeps ends within a radius of the caps.
  CHECK(c.voxels >= 26);
  CHECK(c.voxels <= 36);
}

TEST_CASE("a Y of tubes thins to three branches meeting at one junction", "[imaging][skeleton]") {
  const ImageGeometry g = grid(41, 41, 11);
  std::vector<std::uint8_t> mask(g.voxel_count(), 0);
  const Vec3 centre(20, 20, 5);
  for (double angle : {90.0, 210.0, 330.0}) {
    const double a = angle * M_PI / 180;
    add_tube(g, mask, centre, centre + 15 * Vec3(std::cos(a), std::sin(a), 0), 2.0);
  }
  const std::vector<std::uint8_t> s = curve_skeleton(g, mask);
  const Census c = census(g, s);
  CHECK(c.ends == 3);
  CHECK(c.junction_voxels >= 1);
  CHECK(c.junction_voxels <= 4);
  CHECK(c.isolated == 0);
  CHECK(s[g.linear_index(20, 20, 5)] + s[g.linear_index(20, 21, 5)] + s[g.linear_index(21, 20, 5)] + s[g.linear_index(19, 20, 5)] +
            s[g.linear_index(20, 19, 5)] >= 1);  // the junction sits at the centre
}
