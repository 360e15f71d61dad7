#include "valve/chordae/chordae_network.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <queue>

#include "valve/config/json_reader.hpp"
#include "valve/config/material_config.hpp"
#include "valve/core/error.hpp"

namespace valve {

int ChordaeNetwork::count(ChordType type) const {
  return static_cast<int>(std::count_if(segments.begin(), segments.end(), [&](const ChordSegment& s) { return s.type == type; }));
}

int ChordaeNetwork::count(ChordPointKind kind) const {
  return static_cast<int>(std::count_if(points.begin(), points.end(), [&](const ChordPoint& p) { return p.kind == kind; }));
}

double ChordaeNetwork::unscaled_rest_length(int s) const {
  const ChordSegment& seg = segments[s];
  if (seg.rest_length > 0) return seg.rest_length;
  return (points[seg.from].position - points[seg.to].position).norm();
}

double ChordaeNetwork::rest_length(int s) const { return segments[s].scale * unscaled_rest_length(s); }

const char* to_string(ChordPointKind kind) {
  switch (kind) {
    case ChordPointKind::papillary_tip: return "papillary_tip";
    case ChordPointKind::branch: return "branch";
    case ChordPointKind::insertion: return "insertion";
  }
  return "?";
}

const char* to_string(ChordType type) {
  switch (type) {
    case ChordType::primary: return "primary";
    case ChordType::secondary: return "secondary";
    case ChordType::strut: return "strut";
  }
  return "?";
}

nlohmann::json to_json(const ChordaeNetwork& network) {
  nlohmann::json points = nlohmann::json::array(), segments = nlohmann::json::array();
  for (const auto& p : network.points) {
    nlohmann::json j = {{"kind", to_string(p.kind)}, {"position", {p.position.x(), p.position.y(), p.position.z()}}};
    if (p.kind == ChordPointKind::insertion) j["mesh_node"] = p.mesh_node;
    if (!p.name.empty()) j["name"] = p.name;
    points.push_back(j);
  }
  for (const auto& s : network.segments) {
    nlohmann::json j = {{"from", s.from}, {"to", s.to}, {"type", to_string(s.type)}};
    if (s.scale != 1.0) j["scale"] = s.scale;
    if (s.rest_length > 0) j["rest_length_mm"] = s.rest_length;
    if (!s.material.empty()) j["material"] = s.material;
    if (s.area > 0) j["area_mm2"] = s.area;
    segments.push_back(j);
  }
  nlohmann::json out = {{"diameter_mm", network.diameter}, {"points", points}, {"segments", segments}};
  if (!network.materials.empty()) out["materials"] = network.materials;
  return out;
}

ChordaeNetwork chords_of_types(const ChordaeNetwork& in, const std::vector<std::string>& types) {
  const int n = static_cast<int>(in.points.size());
  std::vector<std::vector<int>> incident(n);
  for (int s = 0; s < static_cast<int>(in.segments.size()); ++s) {
    incident[in.segments[s].from].push_back(s);
    incident[in.segments[s].to].push_back(s);
  }
  // Dijkstra from every papillary tip: distance to the nearest tip and the segment toward it.
  std::vector<double> distance(n, std::numeric_limits<double>::infinity());
  std::vector<int> toward_tip(n, -1);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  for (int p = 0; p < n; ++p)
    if (in.points[p].kind == ChordPointKind::papillary_tip) distance[p] = 0, queue.push({0.0, p});
  while (!queue.empty()) {
    const auto [d, p] = queue.top();
    queue.pop();
    if (d > distance[p]) continue;
    for (int s : incident[p]) {
      const int q = in.segments[s].from == p ? in.segments[s].to : in.segments[s].from;
      const double dq = d + in.unscaled_rest_length(s);
      if (dq < distance[q]) distance[q] = dq, toward_tip[q] = s, queue.push({dq, q});
    }
  }
  std::vector<char> keep(in.segments.size(), 0);
  for (std::size_t s = 0; s < in.segments.size(); ++s) {
    if (std::find(types.begin(), types.end(), to_string(in.segments[s].type)) == types.end()) continue;
    keep[s] = 1;
    const ChordSegment& seg = in.segments[s];
    for (int p = distance[seg.from] <= distance[seg.to] ? seg.from : seg.to; toward_tip[p] >= 0;) {
      const int t = toward_tip[p];
      keep[t] = 1;
      p = in.segments[t].from == p ? in.segments[t].to : in.segments[t].from;
    }
  }
  ChordaeNetwork out;
  out.diameter = in.diameter;
  out.materials = in.materials;
  // Points keep their order in the file, so that per-tip lists (the scene's papillary_tips)
  // still match the tips that remain.
  std::vector<int> index(n, -1);
  for (std::size_t s = 0; s < in.segments.size(); ++s)
    if (keep[s]) index[in.segments[s].from] = index[in.segments[s].to] = 0;
  for (int p = 0; p < n; ++p)
    if (index[p] == 0) index[p] = static_cast<int>(out.points.size()), out.points.push_back(in.points[p]);
  for (std::size_t s = 0; s < in.segments.size(); ++s) {
    if (!keep[s]) continue;
    ChordSegment t = in.segments[s];
    t.from = index[t.from];
    t.to = index[t.to];
    out.segments.push_back(t);
  }
  return out;
}

ChordaeNetwork read_chordae_json(const nlohmann::json& doc, const std::string& file) {
  JsonReader root(doc, file);
  ChordaeNetwork net;
  net.diameter = root.number("diameter_mm", 0.5, 1e-3, 10);
  const json& points = root.raw("points");
  const json& segments = root.raw("segments");
  if (root.has("materials")) {
    const json& materials = root.raw("materials");
    if (!materials.is_object()) root.fail("materials", "an object of chord laws by name", describe_json(materials));
    for (const auto& [name, law] : materials.items()) {
      if (!law.is_object()) root.fail("materials." + name, "a chord law object", describe_json(law));
      JsonReader r(law, file, "materials." + name);
      parse_rod_law(r);  // checked here, so that a file with a bad law is refused where it is read
      r.string("name", "");
      r.string("source", "");
      r.finish();
      net.materials[name] = law;
    }
  }
  if (!points.is_array() || points.empty()) root.fail("points", "a non-empty list of points", points.dump().substr(0, 40));
  if (!segments.is_array() || segments.empty()) root.fail("segments", "a non-empty list of segments", segments.dump().substr(0, 40));
  root.finish();
  for (std::size_t i = 0; i < points.size(); ++i) {
    JsonReader r(points[i], file, "points[" + std::to_string(i) + "]");
    ChordPoint p;
    const std::string kind = r.choice("kind", {"papillary_tip", "branch", "insertion"});
    p.kind = kind == "papillary_tip" ? ChordPointKind::papillary_tip : kind == "branch" ? ChordPointKind::branch : ChordPointKind::insertion;
    const auto x = r.number_list("position");
    if (x.size() != 3 || !std::all_of(x.begin(), x.end(), [](double v) { return std::isfinite(v); }))
      r.fail("position", "[x, y, z] in mm", std::to_string(x.size()) + " numbers");
    p.position = Vec3(x[0], x[1], x[2]);
    p.mesh_node = r.integer("mesh_node", -1, -1);
    p.name = r.string("name", "");
    r.finish();
    net.points.push_back(p);
  }
  const int n = static_cast<int>(net.points.size());
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  std::vector<int> degree(n, 0);
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const std::string where = "segments[" + std::to_string(i) + "]";
    JsonReader r(segments[i], file, where);
    ChordSegment s;
    s.from = r.integer("from", std::nullopt, 0, n - 1);
    s.to = r.integer("to", std::nullopt, 0, n - 1);
    const std::string type = r.choice("type", {"primary", "secondary", "strut"});
    s.type = type == "primary" ? ChordType::primary : type == "secondary" ? ChordType::secondary : ChordType::strut;
    s.scale = r.number("scale", 1.0, 0.2, 5.0);
    s.rest_length = r.number("rest_length_mm", 0.0, 0.0, 1000.0);
    s.material = r.string("material", "");
    if (!s.material.empty() && !net.materials.count(s.material))
      r.fail("material", "a name listed under \"materials\"", "\"" + s.material + "\"");
    s.area = r.number("area_mm2", 0.0, 0.0, 100.0);
    r.finish();
    const double length = (net.points[s.from].position - net.points[s.to].position).norm();
    if (s.from == s.to || length < 1e-6)
      throw_input_error(file, where, "a chord of positive length between two points",
                        "zero length (points " + std::to_string(s.from) + " and " + std::to_string(s.to) + ")");
    parent[find(s.from)] = find(s.to);
    ++degree[s.from], ++degree[s.to];
    net.segments.push_back(s);
  }
  std::vector<char> anchored(n, 0);
  for (int i = 0; i < n; ++i)
    if (net.points[i].kind == ChordPointKind::papillary_tip) anchored[find(i)] = 1;
  for (int i = 0; i < n; ++i) {
    const ChordPoint& p = net.points[i];
    const std::string where = "points[" + std::to_string(i) + "]" + (p.name.empty() ? "" : " (" + p.name + ")");
    if (degree[i] == 0) throw_input_error(file, where, "a point used by a segment", "an unconnected point");
    if (!anchored[find(i)]) throw_input_error(file, where, "a chordae tree connected to a papillary tip", "a tree without one");
  }
  return net;
}

}  // namespace valve
