#include "valve/mechanics/nodal_load.hpp"

#include <cmath>

#include "valve/core/error.hpp"
#include "valve/mesh/topology.hpp"

namespace valve {

VecX biaxial_edge_forces(const TriMesh& mesh, double stress_x, double stress_y, double thickness) {
  VecX f = VecX::Zero(3 * mesh.num_nodes());
  const Topology topo = build_topology(mesh.triangles, mesh.num_nodes());
  const Vec3 centroid = mesh.points.colwise().mean();
  int loaded = 0;
  for (const auto& e : topo.edges) {
    if (e.tris[1] != -1) continue;
    const Vec3 a = mesh.points.row(e.a), b = mesh.points.row(e.b);
    const Vec3 d = b - a;
    Vec3 n(d.y(), -d.x(), 0);  // in-plane normal; orient it away from the patch centre
    const double L = d.norm();
    n /= L;
    if (n.dot(0.5 * (a + b) - centroid) < 0) n = -n;
    Vec3 force = Vec3::Zero();
    if (std::abs(n.x()) > 0.99) force.x() = stress_x * thickness * L * (n.x() > 0 ? 1 : -1);
    else if (std::abs(n.y()) > 0.99) force.y() = stress_y * thickness * L * (n.y() > 0 ? 1 : -1);
    else continue;
    ++loaded;
    node3(f, e.a) += 0.5 * force;
    node3(f, e.b) += 0.5 * force;
  }
  if (loaded == 0) throw InputError("edge_loads: expected boundary edges facing ±x or ±y, found none");
  return f;
}

}  // namespace valve
