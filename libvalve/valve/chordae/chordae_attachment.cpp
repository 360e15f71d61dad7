#include "valve/chordae/chordae_attachment.hpp"

#include <cmath>
#include <cstdio>

#include "valve/core/error.hpp"
#include "valve/mesh/closest_point.hpp"

namespace valve {

void snap_insertions(ChordaeNetwork& network, const MatX3& mesh_points, double tolerance, const std::string& file) {
  for (std::size_t i = 0; i < network.points.size(); ++i) {
    ChordPoint& p = network.points[i];
    if (p.kind != ChordPointKind::insertion) continue;
    double best_d = 0;
    const int best = nearest_point_index(mesh_points, p.position, &best_d);
    if (best < 0 || best_d > tolerance) {
      char found[96];
      std::snprintf(found, sizeof found, "the nearest mesh node %.2f mm away", best_d);
      throw_input_error(file, "points[" + std::to_string(i) + "]" + (p.name.empty() ? "" : " (chord " + p.name + ")"),
                        "an insertion within " + std::to_string(tolerance).substr(0, 5) + " mm of the leaflet mesh", found);
    }
    p.mesh_node = best;
    p.position = mesh_points.row(best).transpose();
  }
}

ChordaeAttachment attach_chordae(const ChordaeNetwork& network, int mesh_nodes, const ChordMaterial& material) {
  ChordaeAttachment a;
  a.mesh_nodes = mesh_nodes;
  const int points = static_cast<int>(network.points.size()), segments = static_cast<int>(network.segments.size());
  auto disk = [](double d) { return M_PI * d * d / 4; };
  std::vector<Rod> segment_rods(segments);
  std::vector<std::vector<int>> incident(points);
  for (int s = 0; s < segments; ++s) {
    const ChordSegment& seg = network.segments[s];
    Rod& rod = segment_rods[s];
    rod.rest_length = network.rest_length(s);
    rod.area = material.diameter > 0 ? disk(material.diameter) : seg.area > 0 ? seg.area : disk(network.diameter);
    const auto named = material.named_laws.find(seg.material);
    rod.law = named != material.named_laws.end() ? named->second : material.default_law;
    incident[seg.from].push_back(s);
    incident[seg.to].push_back(s);
  }
  // Points inside a run: branch points between two segments of one law and section.
  std::vector<char> inside(points, 0);
  if (material.condense_chains)
    for (int p = 0; p < points; ++p) {
      if (network.points[p].kind != ChordPointKind::branch || incident[p].size() != 2) continue;
      const Rod &r0 = segment_rods[incident[p][0]], &r1 = segment_rods[incident[p][1]];
      inside[p] = r0.law == r1.law && r0.area == r1.area;
    }

  std::vector<Vec3> extra;
  for (int p = 0; p < points; ++p) {
    const ChordPoint& cp = network.points[p];
    if (cp.kind == ChordPointKind::insertion) {
      if (cp.mesh_node < 0 || cp.mesh_node >= mesh_nodes)
        throw InputError("chordae: insertion " + (cp.name.empty() ? std::string("(unnamed)") : cp.name) +
                         " is not snapped to a node of the " + std::to_string(mesh_nodes) + "-node mesh (mesh_node " +
                         std::to_string(cp.mesh_node) + ")");
      a.point_node.push_back(cp.mesh_node);
      continue;
    }
    a.point_node.push_back(mesh_nodes + static_cast<int>(extra.size()));
    extra.push_back(cp.position);
    a.extra_roles.push_back(cp.kind == ChordPointKind::papillary_tip || inside[p] ? NodeRole::fixed : NodeRole::free);
  }
  a.extra_points.resize(static_cast<int>(extra.size()), 3);
  for (std::size_t k = 0; k < extra.size(); ++k) a.extra_points.row(k) = extra[k].transpose();
  a.extra_mass.assign(extra.size(), 0.0);
  a.segment_rod.assign(segments, -1);
  a.run_rod.assign(points, -1);
  a.run_fraction.assign(points, 0.0);

  // Each run from an end point (not inside) through the points inside to the next end. A
  // closed loop of points inside (no end) is left to the per-segment rods below.
  auto other_end = [&](int s, int p) { return network.segments[s].from == p ? network.segments[s].to : network.segments[s].from; };
  auto open_length = [&](int s) {
    return (network.points[network.segments[s].from].position - network.points[network.segments[s].to].position).norm();
  };
  auto add_rod = [&](const std::vector<int>& run, int first, int last) {
    Rod rod = segment_rods[run.front()];
    rod.a = a.point_node[first];
    rod.b = a.point_node[last];
    rod.rest_length = 0;
    for (int s : run) {
      rod.rest_length += segment_rods[s].rest_length;
      a.segment_rod[s] = static_cast<int>(a.rods.size());
    }
    // Each end keeps the mass it has with every point a node: half of its own segment's.
    const double half_mass = 0.5 * material.density * rod.area;
    if (rod.a >= mesh_nodes) a.extra_mass[rod.a - mesh_nodes] += half_mass * open_length(run.front());
    if (rod.b >= mesh_nodes) a.extra_mass[rod.b - mesh_nodes] += half_mass * open_length(run.back());
    a.rods.push_back(rod);
  };
  for (int s = 0; s < segments; ++s) {
    if (a.segment_rod[s] >= 0) continue;
    const ChordSegment& seg = network.segments[s];
    if (inside[seg.from] && inside[seg.to]) continue;  // reached from a run's end
    const int first = inside[seg.from] ? seg.to : seg.from;
    std::vector<int> run{s};
    std::vector<int> passed;
    int p = other_end(s, first);
    while (inside[p]) {
      passed.push_back(p);
      const int next = incident[p][0] == run.back() ? incident[p][1] : incident[p][0];
      run.push_back(next);
      p = other_end(next, p);
    }
    add_rod(run, first, p);
    double along = 0;
    for (std::size_t k = 0; k < passed.size(); ++k) {
      along += segment_rods[run[k]].rest_length;
      a.run_rod[passed[k]] = a.segment_rod[s];
      a.run_fraction[passed[k]] = along / a.rods.back().rest_length;
    }
  }
  for (int s = 0; s < segments; ++s)
    if (a.segment_rod[s] < 0) {
      for (int p : {network.segments[s].from, network.segments[s].to}) a.extra_roles[a.point_node[p] - mesh_nodes] = NodeRole::free;
      add_rod({s}, network.segments[s].from, network.segments[s].to);
    }
  return a;
}

MatX3 ChordaeAttachment::point_positions(const VecX& x) const {
  MatX3 positions(static_cast<int>(point_node.size()), 3);
  for (std::size_t p = 0; p < point_node.size(); ++p) {
    if (run_rod[p] < 0) {
      positions.row(static_cast<int>(p)) = node3(x, point_node[p]).transpose();
      continue;
    }
    const Rod& rod = rods[run_rod[p]];
    positions.row(static_cast<int>(p)) = ((1 - run_fraction[p]) * node3(x, rod.a) + run_fraction[p] * node3(x, rod.b)).transpose();
  }
  return positions;
}

std::vector<double> ChordaeAttachment::segment_tensions(const std::vector<double>& rod_tensions) const {
  std::vector<double> t(segment_rod.size());
  for (std::size_t s = 0; s < segment_rod.size(); ++s) t[s] = rod_tensions[segment_rod[s]];
  return t;
}

TriMesh with_chordae_nodes(const TriMesh& mesh, const ChordaeAttachment& attachment) {
  TriMesh m = mesh;
  m.fill_defaults();
  const int n = mesh.num_nodes(), k = static_cast<int>(attachment.extra_points.rows());
  m.points.conservativeResize(n + k, 3);
  m.points.bottomRows(k) = attachment.extra_points;
  if (mesh.initial.rows() == n) {
    m.initial.conservativeResize(n + k, 3);
    m.initial.bottomRows(k) = attachment.extra_points;
  }
  m.roles.insert(m.roles.end(), attachment.extra_roles.begin(), attachment.extra_roles.end());
  m.boundary.resize(n + k, BoundaryType::interior);
  return m;
}

}  // namespace valve
