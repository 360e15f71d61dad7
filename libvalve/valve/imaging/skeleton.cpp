#include "valve/imaging/skeleton.hpp"

#include <array>
#include <cstdlib>

namespace valve {
namespace {

constexpr int kCentre = 13;

int cell(int x, int y, int z) { return x + 3 * y + 9 * z; }

// Distance class of a cell of the 3 × 3 × 3 block from the centre: 1 face, 2 edge, 3 corner.
int manhattan(int n) { return std::abs(n % 3 - 1) + std::abs(n / 3 % 3 - 1) + std::abs(n / 9 - 1); }

// Components of the cells `in` (in[n] true) of the block under 26- or 6-adjacency; returns
// the number of components, and in `touches_face` how many contain a face neighbour.
int components(const std::array<bool, 27>& in, bool six, int* touches_face) {
  std::array<bool, 27> seen{};
  int count = 0, with_face = 0;
  for (int start = 0; start < 27; ++start) {
    if (!in[start] || seen[start]) continue;
    ++count;
    bool face = false;
    int stack[27], top = 0;
    stack[top++] = start;
    seen[start] = true;
    while (top > 0) {
      const int a = stack[--top];
      face = face || manhattan(a) == 1;
      for (int b = 0; b < 27; ++b) {
        if (!in[b] || seen[b]) continue;
        const int dx = std::abs(a % 3 - b % 3), dy = std::abs(a / 3 % 3 - b / 3 % 3), dz = std::abs(a / 9 - b / 9);
        const bool adjacent = six ? dx + dy + dz == 1 : (dx <= 1 && dy <= 1 && dz <= 1);
        if (adjacent) seen[b] = true, stack[top++] = b;
      }
    }
    with_face += face;
  }
  if (touches_face) *touches_face = with_face;
  return count;
}

}  // namespace

bool is_simple_point(const std::uint8_t cube[27]) {
  std::array<bool, 27> object{}, background{};
  bool any = false;
  for (int n = 0; n < 27; ++n) {
    if (n == kCentre) continue;
    object[n] = cube[n] != 0;
    any = any || object[n];
    background[n] = cube[n] == 0 && manhattan(n) <= 2;  // N18
  }
  if (!any) return false;  // an isolated voxel is a component of its own
  if (components(object, false, nullptr) != 1) return false;
  int with_face = 0;
  components(background, true, &with_face);
  return with_face == 1;
}

std::vector<std::uint8_t> curve_skeleton(const ImageGeometry& g, std::vector<std::uint8_t> mask) {
  const int nx = g.size[0], ny = g.size[1], nz = g.size[2];
  auto at = [&](int i, int j, int k) -> std::uint8_t {
    if (i < 0 || j < 0 || k < 0 || i >= nx || j >= ny || k >= nz) return 0;
    return mask[g.linear_index(i, j, k)] != 0;
  };
  std::vector<std::array<int, 3>> object;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        if (mask[g.linear_index(i, j, k)]) object.push_back({i, j, k}), mask[g.linear_index(i, j, k)] = 1;

  auto block = [&](const std::array<int, 3>& v, std::uint8_t cube[27], int& neighbours) {
    neighbours = 0;
    for (int z = 0; z < 3; ++z)
      for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 3; ++x) {
          const int n = cell(x, y, z);
          cube[n] = at(v[0] + x - 1, v[1] + y - 1, v[2] + z - 1);
          if (n != kCentre) neighbours += cube[n];
        }
  };
  auto removable = [&](const std::array<int, 3>& v) {
    std::uint8_t cube[27];
    int neighbours = 0;
    block(v, cube, neighbours);
    return neighbours >= 2 && is_simple_point(cube);  // curve ends (one neighbour) stay
  };
  const int directions[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (bool changed = true; changed;) {
    changed = false;
    for (const auto& d : directions) {
      std::vector<std::size_t> candidates;
      for (std::size_t n = 0; n < object.size(); ++n) {
        const auto& v = object[n];
        if (!at(v[0], v[1], v[2]) || at(v[0] + d[0], v[1] + d[1], v[2] + d[2])) continue;
        if (removable(v)) candidates.push_back(n);
      }
      for (std::size_t n : candidates) {
        const auto& v = object[n];
        if (!removable(v)) continue;  // an earlier removal of this sub-iteration changed it
        mask[g.linear_index(v[0], v[1], v[2])] = 0;
        changed = true;
      }
    }
    // Drop removed voxels from the work list.
    std::size_t kept = 0;
    for (const auto& v : object)
      if (at(v[0], v[1], v[2])) object[kept++] = v;
    object.resize(kept);
  }
  return mask;
}

}  // namespace valve
