#include "valve/chordae/slicer_markups.hpp"

#include <algorithm>
#include <cmath>

#include "valve/mesh/topology.hpp"
#include "valve/config/json_reader.hpp"
#include "valve/core/atomic_file.hpp"
#include "valve/core/error.hpp"

namespace valve {

namespace {

int find_or_add(ChordaeNetwork& net, const Vec3& p, ChordPointKind kind, double merge, const std::string& name) {
  for (std::size_t i = 0; i < net.points.size(); ++i)
    if ((net.points[i].position - p).norm() <= merge) {
      // A tip stays a tip; a point reached by several curves in the middle is a branch.
      if (net.points[i].kind != kind && net.points[i].kind != ChordPointKind::papillary_tip) net.points[i].kind = ChordPointKind::branch;
      return static_cast<int>(i);
    }
  ChordPoint cp;
  cp.kind = kind;
  cp.position = p;
  cp.name = name;
  net.points.push_back(cp);
  return static_cast<int>(net.points.size()) - 1;
}

}  // namespace

ChordaeNetwork read_slicer_curves(const std::vector<std::filesystem::path>& files, double merge) {
  ChordaeNetwork net;
  for (const auto& file : files) {
    const json doc = load_json_file(file);
    const std::string f = file.string();
    if (!doc.is_object() || !doc.contains("markups") || !doc["markups"].is_array() || doc["markups"].empty())
      throw_input_error(f, "markups", "a non-empty list of Slicer markups", doc.is_object() && doc.contains("markups") ? describe_json(doc["markups"]) : "no markups key");
    for (std::size_t m = 0; m < doc["markups"].size(); ++m) {
      const json& mk = doc["markups"][m];
      const std::string where = "markups[" + std::to_string(m) + "]";
      if (!mk.is_object()) throw_input_error(f, where, "a markup object", describe_json(mk));
      const std::string type = mk.value("type", "");
      if (type != "Curve" && type != "OpenCurve")
        throw_input_error(f, where + ".type", "Curve (a chord from a papillary tip to an insertion)", "\"" + type + "\"");
      const std::string system = mk.value("coordinateSystem", "LPS");
      if (system != "LPS" && system != "RAS") throw_input_error(f, where + ".coordinateSystem", "LPS or RAS", "\"" + system + "\"");
      const json cps = mk.value("controlPoints", json::array());
      if (!cps.is_array() || cps.size() < 2)
        throw_input_error(f, where + ".controlPoints", "at least 2 points (tip, insertion)", describe_json(cps));
      std::string name = mk.value("name", "");
      std::vector<Vec3> pts;
      for (std::size_t k = 0; k < cps.size(); ++k) {
        const json pos = cps[k].is_object() ? cps[k].value("position", json()) : json();
        if (!pos.is_array() || pos.size() != 3 || !pos[0].is_number() || !pos[1].is_number() || !pos[2].is_number())
          throw_input_error(f, where + ".controlPoints[" + std::to_string(k) + "].position", "[x, y, z]", describe_json(pos));
        Vec3 p(pos[0].get<double>(), pos[1].get<double>(), pos[2].get<double>());
        if (system == "RAS") p.x() = -p.x(), p.y() = -p.y();
        pts.push_back(p);
      }
      const bool strut = name.find("strut") != std::string::npos || name.find("Strut") != std::string::npos;
      int prev = find_or_add(net, pts.front(), ChordPointKind::papillary_tip, merge, "");
      for (std::size_t k = 1; k < pts.size(); ++k) {
        const bool last = k + 1 == pts.size();
        const int cur = find_or_add(net, pts[k], last ? ChordPointKind::insertion : ChordPointKind::branch, merge, last ? name : "");
        if (cur == prev) throw_input_error(f, where + ".controlPoints[" + std::to_string(k) + "]", "a point apart from the previous one",
                                           "a zero-length chord (closer than the merge distance)");
        ChordSegment s;
        s.from = prev;
        s.to = cur;
        s.type = strut ? ChordType::strut : ChordType::primary;
        net.segments.push_back(s);
        prev = cur;
      }
    }
  }
  // Duplicate segments (two curves sharing a stretch) count once.
  std::vector<ChordSegment> unique;
  for (const auto& s : net.segments)
    if (std::none_of(unique.begin(), unique.end(), [&](const ChordSegment& u) {
          return (u.from == s.from && u.to == s.to) || (u.from == s.to && u.to == s.from);
        }))
      unique.push_back(s);
  net.segments = unique;
  return net;
}

void classify_by_insertion(ChordaeNetwork& net, const TriMesh& mesh) {
  const int n = static_cast<int>(net.points.size());
  // Walk from every insertion toward the tip, marking segments primary or secondary; a
  // segment feeding both kinds (a trunk before a branch) is primary, as it tethers the edge.
  std::vector<int> mark(net.segments.size(), -1);  // 0 secondary, 1 primary
  for (int p = 0; p < n; ++p) {
    if (net.points[p].kind != ChordPointKind::insertion || net.points[p].mesh_node < 0) continue;
    const int node = net.points[p].mesh_node;
    const int primary = node < static_cast<int>(mesh.boundary.size()) && mesh.boundary[node] == BoundaryType::free_edge;
    int cur = p;
    for (int guard = 0; guard < n; ++guard) {
      int next = -1;
      for (std::size_t s = 0; s < net.segments.size(); ++s) {
        const ChordSegment& seg = net.segments[s];
        if (seg.to == cur && mark[s] < primary) {
          mark[s] = primary;
          next = seg.from;
          break;
        }
      }
      if (next < 0 || net.points[next].kind == ChordPointKind::papillary_tip) break;
      cur = next;
    }
  }
  for (std::size_t s = 0; s < net.segments.size(); ++s)
    if (net.segments[s].type != ChordType::strut && mark[s] >= 0)
      net.segments[s].type = mark[s] == 1 ? ChordType::primary : ChordType::secondary;
}

void write_slicer_curves(const std::filesystem::path& path, const std::vector<MarkupCurve>& curves) {
  json markups = json::array();
  for (const auto& c : curves) {
    if (c.points.rows() < 2) continue;
    if (!c.points.allFinite()) throw NumericalError(path.string() + ": curve " + c.name + " has a non-finite point");
    json points = json::array();
    for (Eigen::Index i = 0; i < c.points.rows(); ++i)
      points.push_back({{"id", std::to_string(i + 1)},
                        {"label", c.name + "-" + std::to_string(i + 1)},
                        {"position", {c.points(i, 0), c.points(i, 1), c.points(i, 2)}},
                        {"positionStatus", "defined"},
                        {"locked", true}});
    markups.push_back({{"type", c.closed ? "ClosedCurve" : "Curve"},
                       {"coordinateSystem", "LPS"},
                       {"coordinateUnits", "mm"},
                       {"name", c.name},
                       {"locked", true},
                       {"controlPoints", points}});
  }
  const json doc = {
      {"@schema", "https://raw.githubusercontent.com/slicer/slicer/master/Modules/Loadable/Markups/Resources/Schema/markups-schema-v1.0.3.json#"},
      {"markups", markups}};
  write_file_atomic(path, doc.dump(2) + "\n");
}

namespace {
MatX3 curve_points(const std::vector<int>& nodes, const VecX& x) {
  MatX3 p(static_cast<Eigen::Index>(nodes.size()), 3);
  for (std::size_t i = 0; i < nodes.size(); ++i) p.row(static_cast<Eigen::Index>(i)) = x.segment<3>(3 * nodes[i]).transpose();
  return p;
}
}  // namespace

namespace {
// The maximal runs of consecutive nodes of a boundary loop that satisfy `in`, in loop order; the
// whole loop, closed, when every node does. `with_ends` adds the loop neighbour at each end of a
// run (a free edge ends at the attached corners).
template <class In>
std::vector<std::pair<std::vector<int>, bool>> loop_runs(const std::vector<int>& loop, In in, bool with_ends) {
  const std::size_t n = loop.size();
  std::size_t s = 0;
  while (s < n && in(loop[s])) ++s;
  if (s == n) return {{loop, true}};
  std::vector<std::pair<std::vector<int>, bool>> runs;
  std::vector<int> run;
  for (std::size_t k = 1; k <= n; ++k) {
    const int node = loop[(s + k) % n], prev = loop[(s + k - 1) % n];
    if (in(node)) {
      if (run.empty() && with_ends) run.push_back(prev);
      run.push_back(node);
    } else if (!run.empty()) {
      if (with_ends) run.push_back(node);
      runs.emplace_back(run, false);
      run.clear();
    }
  }
  return runs;
}

std::string numbered(const std::string& name, int k) { return k == 0 ? name : name + " " + std::to_string(k + 1); }
}  // namespace

std::vector<MarkupCurve> valve_landmark_curves(const TriMesh& mesh, const VecX& x, const std::vector<int>* coapting) {
  // From the boundary loops rather than one ring per mesh: a leaflet's attachment is an arc
  // that must not be drawn closed across its free edge, and a valve of separate leaflets has
  // one arc per leaflet.
  const Topology topo = build_topology(mesh.triangles, mesh.num_nodes());
  auto attached = [&](int i) { return mesh.roles[i] == NodeRole::fixed || mesh.boundary[i] == BoundaryType::attached; };
  auto free_edge = [&](int i) { return mesh.boundary[i] == BoundaryType::free_edge; };
  std::vector<MarkupCurve> annulus, edges, lines;
  for (const auto& loop : topo.loops) {
    for (const auto& [run, closed] : loop_runs(loop, attached, false))
      annulus.push_back({numbered("annulus", static_cast<int>(annulus.size())), curve_points(run, x), closed});
    for (const auto& [run, closed] : loop_runs(loop, free_edge, true)) {
      edges.push_back({numbered("free edge", static_cast<int>(edges.size())), curve_points(run, x), closed});
      if (!coapting) continue;
      // An open edge ends in a sentinel (-1) so that no stretch wraps from its last node to its first.
      std::vector<int> nodes = run;
      if (!closed) nodes.push_back(-1);
      for (const auto& [part, whole] : loop_runs(nodes, [&](int i) { return i >= 0 && (*coapting)[i] == 1; }, false))
        lines.push_back({numbered("coaptation line", static_cast<int>(lines.size())), curve_points(part, x), closed && whole});
    }
  }
  for (auto* group : {&edges, &lines}) annulus.insert(annulus.end(), group->begin(), group->end());
  return annulus;
}

}  // namespace valve
