#include "valve/mesh/subdivide.hpp"

#include <algorithm>
#include <map>

#include "valve/mesh/topology.hpp"

namespace valve {

TriMesh subdivide_midpoint(const TriMesh& mesh) {
  TriMesh out;
  const int n = mesh.num_nodes();
  std::map<std::pair<int, int>, int> midpoint;
  std::vector<Vec3> extra;
  std::vector<NodeRole> roles = mesh.roles;
  std::vector<BoundaryType> boundary = mesh.boundary;
  auto mid = [&](int a, int b) {
    const auto key = std::minmax(a, b);
    auto it = midpoint.find(key);
    if (it != midpoint.end()) return it->second;
    const int id = n + static_cast<int>(extra.size());
    extra.push_back(0.5 * (mesh.points.row(a) + mesh.points.row(b)).transpose());
    roles.push_back(mesh.roles[a] == mesh.roles[b] ? mesh.roles[a] : NodeRole::free);
    boundary.push_back(mesh.boundary[a] == mesh.boundary[b] ? mesh.boundary[a] : BoundaryType::interior);
    midpoint.emplace(key, id);
    return id;
  };
  for (int f = 0; f < mesh.num_triangles(); ++f) {
    const Tri& t = mesh.triangles[f];
    const int ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
    for (const Tri& child : {Tri(t[0], ab, ca), Tri(ab, t[1], bc), Tri(ca, bc, t[2]), Tri(ab, bc, ca)}) {
      out.triangles.push_back(child);
      out.leaflet.push_back(mesh.leaflet.empty() ? 0 : mesh.leaflet[f]);
    }
  }
  // A midpoint between two boundary nodes is only on the boundary if the edge is.
  for (const Edge& e : build_topology(mesh.triangles, n).edges)
    if (e.tris[1] >= 0) {
      const int id = midpoint.at({e.a, e.b});
      boundary[id] = BoundaryType::interior;
      roles[id] = NodeRole::free;
    }
  out.points.resize(n + static_cast<int>(extra.size()), 3);
  out.points.topRows(n) = mesh.points;
  for (std::size_t e = 0; e < extra.size(); ++e) out.points.row(n + e) = extra[e].transpose();
  out.roles = roles;
  out.boundary = boundary;
  out.fiber.resize(out.num_triangles(), 3);
  for (int f = 0; f < mesh.num_triangles(); ++f)
    for (int c = 0; c < 4; ++c) out.fiber.row(4 * f + c) = mesh.fiber.row(f);
  out.fill_defaults();
  return out;
}

}  // namespace valve
