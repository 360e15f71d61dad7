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
  std::vector<Vec3> extra;
  for (const ChordPoint& p : network.points) {
    if (p.kind == ChordPointKind::insertion) {
      if (p.mesh_node < 0 || p.mesh_node >= mesh_nodes)
        throw InputError("chordae: insertion " + (p.name.empty() ? std::string("(unnamed)") : p.name) +
                         " is not snapped to a node of the " + std::to_string(mesh_nodes) + "-node mesh (mesh_node " +
                         std::to_string(p.mesh_node) + ")");
      a.point_node.push_back(p.mesh_node);
      continue;
    }
    a.point_node.push_back(mesh_nodes + static_cast<int>(extra.size()));
    extra.push_back(p.position);
    a.extra_roles.push_back(p.kind == ChordPointKind::papillary_tip ? NodeRole::fixed : NodeRole::free);
  }
  a.extra_points.resize(static_cast<int>(extra.size()), 3);
  for (std::size_t k = 0; k < extra.size(); ++k) a.extra_points.row(k) = extra[k].transpose();
  a.extra_mass.assign(extra.size(), 0.0);
  auto disk = [](double d) { return M_PI * d * d / 4; };
  for (int s = 0; s < static_cast<int>(network.segments.size()); ++s) {
    const ChordSegment& seg = network.segments[s];
    Rod rod;
    rod.a = a.point_node[seg.from];
    rod.b = a.point_node[seg.to];
    rod.rest_length = network.rest_length(s);
    rod.area = material.diameter > 0 ? disk(material.diameter) : seg.area > 0 ? seg.area : disk(network.diameter);
    const auto named = material.named_laws.find(seg.material);
    rod.law = named != material.named_laws.end() ? named->second : material.default_law;
    a.rods.push_back(rod);
    const double half_mass = 0.5 * material.density * rod.area * (network.points[seg.from].position - network.points[seg.to].position).norm();
    for (int node : {rod.a, rod.b})
      if (node >= mesh_nodes) a.extra_mass[node - mesh_nodes] += half_mass;
  }
  return a;
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
