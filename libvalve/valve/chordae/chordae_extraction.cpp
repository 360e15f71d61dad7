#include "valve/chordae/chordae_extraction.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <limits>
#include <set>
#include <unordered_map>

#include "valve/core/error.hpp"
#include "valve/imaging/skeleton.hpp"
#include "valve/mesh/nearest_points.hpp"

namespace valve {
namespace {

using Voxel = std::array<int, 3>;

struct Edge {
  int a = 0, b = 0;
  double length = 0;  // along the voxel path, mm
  bool alive = true;
};

// Whether a voxel labelled `label` lies within `radius` mm of voxel v.
bool near_label(const LabelMap& map, const Voxel& v, std::uint8_t label, double radius) {
  const ImageGeometry& g = map.geometry;
  const Vec3 p = g.physical_point(Vec3(v[0], v[1], v[2]));
  const int r[3] = {static_cast<int>(std::ceil(radius / g.spacing[0])), static_cast<int>(std::ceil(radius / g.spacing[1])),
                    static_cast<int>(std::ceil(radius / g.spacing[2]))};
  for (int k = std::max(0, v[2] - r[2]); k <= std::min(g.size[2] - 1, v[2] + r[2]); ++k)
    for (int j = std::max(0, v[1] - r[1]); j <= std::min(g.size[1] - 1, v[1] + r[1]); ++j)
      for (int i = std::max(0, v[0] - r[0]); i <= std::min(g.size[0] - 1, v[0] + r[0]); ++i)
        if (map.labels[g.linear_index(i, j, k)] == label && (g.physical_point(Vec3(i, j, k)) - p).norm() <= radius) return true;
  return false;
}

}  // namespace

ChordaeNetwork chordae_from_labels(const LabelMap& labels, const ChordaeExtractionOptions& options, const std::string& file,
                                   ChordaeExtractionSummary* summary_out) {
  const ImageGeometry& g = labels.geometry;
  ChordaeExtractionSummary summary;
  std::vector<std::uint8_t> mask(g.voxel_count(), 0);
  for (std::size_t i = 0; i < mask.size(); ++i)
    if (labels.labels[i] == label_chordae) mask[i] = 1, ++summary.chordae_voxels;
  if (summary.chordae_voxels == 0) throw_input_error(file, "labels", "chordae voxels (label 2)", "none");
  const std::vector<std::uint8_t> skeleton = curve_skeleton(g, std::move(mask));

  // Skeleton voxels and their 26-neighbours.
  std::vector<Voxel> voxels;
  std::unordered_map<std::size_t, int> id_of;
  for (int k = 0; k < g.size[2]; ++k)
    for (int j = 0; j < g.size[1]; ++j)
      for (int i = 0; i < g.size[0]; ++i)
        if (skeleton[g.linear_index(i, j, k)]) id_of[g.linear_index(i, j, k)] = static_cast<int>(voxels.size()), voxels.push_back({i, j, k});
  summary.skeleton_voxels = static_cast<long>(voxels.size());
  const int nv = static_cast<int>(voxels.size());
  std::vector<std::vector<int>> neighbours(nv);
  for (int v = 0; v < nv; ++v)
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int i = voxels[v][0] + dx, j = voxels[v][1] + dy, k = voxels[v][2] + dz;
          if ((dx == 0 && dy == 0 && dz == 0) || i < 0 || j < 0 || k < 0 || i >= g.size[0] || j >= g.size[1] || k >= g.size[2]) continue;
          const auto it = id_of.find(g.linear_index(i, j, k));
          if (it != id_of.end()) neighbours[v].push_back(it->second);
        }
  auto point = [&](int v) { return g.physical_point(Vec3(voxels[v][0], voxels[v][1], voxels[v][2])); };

  // Graph vertices: curve ends, and clusters of 26-adjacent junction voxels.
  std::vector<int> vertex_of(nv, -1);
  std::vector<std::vector<int>> vertex_voxels;
  for (int v = 0; v < nv; ++v)
    if (neighbours[v].size() == 1) vertex_of[v] = static_cast<int>(vertex_voxels.size()), vertex_voxels.push_back({v});
  for (int v = 0; v < nv; ++v) {
    if (neighbours[v].size() < 3 || vertex_of[v] >= 0) continue;
    const int id = static_cast<int>(vertex_voxels.size());
    vertex_voxels.emplace_back();
    std::vector<int> stack{v};
    vertex_of[v] = id;
    while (!stack.empty()) {
      const int a = stack.back();
      stack.pop_back();
      vertex_voxels[id].push_back(a);
      for (int b : neighbours[a])
        if (neighbours[b].size() >= 3 && vertex_of[b] < 0) vertex_of[b] = id, stack.push_back(b);
    }
    ++summary.junctions;
  }
  const int nvert = static_cast<int>(vertex_voxels.size());
  auto vertex_position = [&](int x) {
    Vec3 p = Vec3::Zero();
    for (int v : vertex_voxels[x]) p += point(v) / static_cast<double>(vertex_voxels[x].size());
    return p;
  };

  // Edges: voxel paths between vertices (each traced once; loops without a vertex ignored).
  std::vector<Edge> edges;
  std::vector<char> visited(nv, 0);
  std::set<std::pair<int, int>> direct;
  for (int v = 0; v < nv; ++v) {
    if (vertex_of[v] < 0) continue;
    for (int w : neighbours[v]) {
      if (vertex_of[w] >= 0) {
        const int a = vertex_of[v], b = vertex_of[w];
        if (a != b && direct.insert({std::min(a, b), std::max(a, b)}).second) edges.push_back({a, b, (point(v) - point(w)).norm()});
        continue;
      }
      if (visited[w]) continue;
      visited[w] = 1;
      int previous = v, current = w;
      double length = (point(v) - point(w)).norm();
      while (current >= 0 && vertex_of[current] < 0) {
        int next = -1;
        for (int x : neighbours[current])
          if (x != previous) next = x;
        if (next < 0 || (vertex_of[next] < 0 && visited[next])) {
          current = -1;  // a dead end or a closed loop
          break;
        }
        length += (point(current) - point(next)).norm();
        previous = current;
        current = next;
        if (vertex_of[current] < 0) visited[current] = 1;
      }
      if (current >= 0 && vertex_of[current] != vertex_of[v]) edges.push_back({vertex_of[v], vertex_of[current], length});
    }
  }

  std::vector<int> degree(nvert, 0);
  for (const Edge& e : edges) ++degree[e.a], ++degree[e.b];
  // Spurs, one at a time so that degrees stay exact; then join the two branches of any
  // vertex left with two.
  for (bool again = true; again;) {
    again = false;
    for (Edge& e : edges) {
      if (!e.alive || e.length >= options.min_spur_mm) continue;
      if ((degree[e.a] == 1 && degree[e.b] >= 3) || (degree[e.b] == 1 && degree[e.a] >= 3)) {
        e.alive = false;
        --degree[e.a], --degree[e.b];
        ++summary.spurs_removed;
        again = true;
      }
    }
  }
  for (bool again = true; again;) {
    again = false;
    for (int x = 0; x < nvert; ++x) {
      if (degree[x] != 2) continue;
      Edge* pair[2] = {nullptr, nullptr};
      for (Edge& e : edges)
        if (e.alive && (e.a == x || e.b == x)) (pair[0] ? pair[1] : pair[0]) = &e;
      const int u = pair[0]->a == x ? pair[0]->b : pair[0]->a, w = pair[1]->a == x ? pair[1]->b : pair[1]->a;
      pair[0]->alive = pair[1]->alive = false;
      degree[x] = 0;
      if (u == w) {  // a loop through x: nothing to tether
        degree[u] -= 2;
      } else {
        edges.push_back({u, w, pair[0]->length + pair[1]->length});
      }
      again = true;
    }
  }

  // Ends: insertions near leaflet tissue, tips elsewhere.
  std::vector<ChordPointKind> kind(nvert, ChordPointKind::branch);
  for (int x = 0; x < nvert; ++x) {
    if (degree[x] != 1) continue;
    const Voxel& end = voxels[vertex_voxels[x].front()];
    const double r = options.insertion_distance_mm;
    kind[x] = !near_label(labels, end, label_other_tissue, r) && near_label(labels, end, label_leaflet, r)
                  ? ChordPointKind::insertion
                  : ChordPointKind::papillary_tip;
  }

  std::vector<std::vector<int>> incident(nvert);
  for (std::size_t e = 0; e < edges.size(); ++e)
    if (edges[e].alive) incident[edges[e].a].push_back(static_cast<int>(e)), incident[edges[e].b].push_back(static_cast<int>(e));

  // Convergence tips: where the chords of one papillary muscle meet, thinning leaves a
  // junction, not an end. A junction farther from leaflet tissue than every vertex it is
  // joined to is where its chords come from, so it is a tip; without this, the chords of a
  // muscle the scan shows only as their meeting point would hang leaflet to leaflet. A
  // junction joined to a tip end is a branch of that tip's chord (an open leaflet can hang
  // closer to the muscle than the branch is).
  if (options.convergence_clearance_mm > 0) {
    std::vector<Vec3> leaflet_points;
    for (int k = 0; k < g.size[2]; ++k)
      for (int j = 0; j < g.size[1]; ++j)
        for (int i = 0; i < g.size[0]; ++i)
          if (labels.labels[g.linear_index(i, j, k)] == label_leaflet) leaflet_points.push_back(g.physical_point(Vec3(i, j, k)));
    MatX3 leaflet(static_cast<Eigen::Index>(leaflet_points.size()), 3);
    for (std::size_t i = 0; i < leaflet_points.size(); ++i) leaflet.row(static_cast<Eigen::Index>(i)) = leaflet_points[i].transpose();
    const NearestPoints nearest_leaflet(leaflet);
    std::vector<double> clearance(nvert, std::numeric_limits<double>::infinity());  // no leaflet: no tip is added
    for (int x = 0; x < nvert; ++x)
      if (degree[x] > 0 && !leaflet_points.empty()) nearest_leaflet.nearest(vertex_position(x), &clearance[x]);
    for (int x = 0; x < nvert; ++x) {
      if (degree[x] < 3 || clearance[x] < options.convergence_clearance_mm) continue;
      bool farthest = true;
      for (int e : incident[x]) {
        const int y = edges[e].a == x ? edges[e].b : edges[e].a;
        farthest = farthest && clearance[y] < clearance[x] && !(degree[y] == 1 && kind[y] == ChordPointKind::papillary_tip);
      }
      if (farthest) kind[x] = ChordPointKind::papillary_tip, ++summary.convergence_tips;
    }
  }

  // Components with a tip and an insertion; hop distance from the nearest tip for direction.
  std::vector<int> component(nvert, -1);
  std::vector<char> keep_component;
  for (int s = 0; s < nvert; ++s) {
    if (degree[s] == 0 || component[s] >= 0) continue;
    const int c = static_cast<int>(keep_component.size());
    bool tip = false, insertion = false;
    std::vector<int> stack{s};
    component[s] = c;
    while (!stack.empty()) {
      const int a = stack.back();
      stack.pop_back();
      tip = tip || kind[a] == ChordPointKind::papillary_tip;
      insertion = insertion || kind[a] == ChordPointKind::insertion;
      for (int e : incident[a]) {
        const int b = edges[e].a == a ? edges[e].b : edges[e].a;
        if (component[b] < 0) component[b] = c, stack.push_back(b);
      }
    }
    keep_component.push_back(tip && insertion);
    ++summary.components;
    summary.components_dropped += !(tip && insertion);
  }
  std::vector<int> hops(nvert, -1);
  std::deque<int> queue;
  for (int x = 0; x < nvert; ++x)
    if (degree[x] > 0 && keep_component[component[x]] && kind[x] == ChordPointKind::papillary_tip) hops[x] = 0, queue.push_back(x);
  while (!queue.empty()) {
    const int a = queue.front();
    queue.pop_front();
    for (int e : incident[a]) {
      const int b = edges[e].a == a ? edges[e].b : edges[e].a;
      if (hops[b] < 0) hops[b] = hops[a] + 1, queue.push_back(b);
    }
  }

  ChordaeNetwork net;
  std::vector<int> point_of(nvert, -1);
  for (int x = 0; x < nvert; ++x) {
    if (degree[x] == 0 || !keep_component[component[x]]) continue;
    ChordPoint p;
    p.kind = kind[x];
    p.position = vertex_position(x);
    p.name = std::string(to_string(kind[x])) + " " + std::to_string(x);
    point_of[x] = static_cast<int>(net.points.size());
    net.points.push_back(p);
    if (kind[x] == ChordPointKind::insertion) ++summary.insertions;
    if (kind[x] == ChordPointKind::papillary_tip) {
      ++summary.papillary_tips;
      summary.tips_on_other_tissue += near_label(labels, voxels[vertex_voxels[x].front()], label_other_tissue, options.insertion_distance_mm);
    }
  }
  for (const Edge& e : edges) {
    if (!e.alive || point_of[e.a] < 0) continue;
    ChordSegment s;
    const bool forward = hops[e.a] <= hops[e.b];
    s.from = point_of[forward ? e.a : e.b];
    s.to = point_of[forward ? e.b : e.a];
    s.type = ChordType::secondary;
    const double length = (net.points[s.from].position - net.points[s.to].position).norm();
    if (length <= 0) continue;
    summary.total_length_mm += length;
    net.segments.push_back(s);
  }
  if (net.segments.empty())
    throw_input_error(file, "labels", "chordae joining leaflet tissue to a papillary tip",
                      std::to_string(summary.components) + " skeleton pieces, none with both ends");
  if (summary_out) *summary_out = summary;
  return net;
}

}  // namespace valve
