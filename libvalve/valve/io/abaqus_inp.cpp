#include "valve/io/abaqus_inp.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>

#include "valve/core/error.hpp"

namespace valve {
namespace {

std::string upper(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::toupper(c); });
  return s;
}

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
}

std::vector<std::string> split_commas(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string item;
  while (std::getline(ss, item, ',')) out.push_back(trim(item));
  if (!out.empty() && out.back().empty()) out.pop_back();  // trailing comma
  return out;
}

// The value of KEY=VALUE among a keyword line's parameters ("" if absent).
std::string parameter(const std::vector<std::string>& words, const std::string& key) {
  for (std::size_t i = 1; i < words.size(); ++i) {
    const auto eq = words[i].find('=');
    if (eq != std::string::npos && upper(trim(words[i].substr(0, eq))) == key) return trim(words[i].substr(eq + 1));
  }
  return "";
}

bool has_word(const std::vector<std::string>& words, const std::string& key) {
  for (std::size_t i = 1; i < words.size(); ++i)
    if (upper(words[i]) == key) return true;
  return false;
}

}  // namespace

AbaqusModel read_abaqus_inp(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw_input_error(path.string(), "", "a readable Abaqus .inp file", "nothing there");
  AbaqusModel m;
  std::vector<Vec3> points;
  enum class Block { none, node, element, nset } block = Block::none;
  std::string nset;
  bool generate = false;
  std::string line;
  int number = 0;
  auto fail = [&](const std::string& expected) {
    throw_input_error(path.string(), "line " + std::to_string(number), expected, "\"" + trim(line).substr(0, 60) + "\"");
  };
  auto to_int = [&](const std::string& s) {
    try {
      std::size_t used = 0;
      const int v = std::stoi(s, &used);
      if (used != s.size()) fail("integer ids");
      return v;
    } catch (const std::logic_error&) {
      fail("integer ids");
    }
    return 0;
  };
  auto to_double = [&](const std::string& s) {
    try {
      std::size_t used = 0;
      const double v = std::stod(s, &used);
      if (used != s.size() || !std::isfinite(v)) fail("finite node coordinates");
      return v;
    } catch (const std::logic_error&) {
      fail("finite node coordinates");
    }
    return 0.0;
  };
  while (std::getline(in, line)) {
    ++number;
    const std::string t = trim(line);
    if (t.empty() || t.rfind("**", 0) == 0) continue;
    if (t[0] == '*') {
      const auto words = split_commas(t);
      const std::string keyword = upper(words[0]);
      block = Block::none;
      if (keyword == "*NODE") {
        block = Block::node;
        const std::string set = upper(parameter(words, "NSET"));
        if (!set.empty()) nset = set, m.node_sets[nset];  // filled as nodes come
        else nset.clear();
      } else if (keyword == "*ELEMENT") {
        block = Block::element;
        m.blocks.push_back({upper(parameter(words, "TYPE")), parameter(words, "ELSET"), {}, {}});
      } else if (keyword == "*NSET") {
        block = Block::nset;
        nset = upper(parameter(words, "NSET"));
        generate = has_word(words, "GENERATE");
        m.node_sets[nset];
      }
      continue;
    }
    const auto f = split_commas(t);
    if (block == Block::node) {
      if (f.size() < 4) fail("a node line: id, x, y, z");
      const int id = to_int(f[0]);
      if (!m.row_of_node.emplace(id, static_cast<int>(points.size())).second) fail("unique node ids");
      m.node_ids.push_back(id);
      points.emplace_back(to_double(f[1]), to_double(f[2]), to_double(f[3]));
      if (!nset.empty()) m.node_sets[nset].push_back(id);
    } else if (block == Block::element) {
      if (f.size() < 3) fail("an element line: id, node ids");
      auto& b = m.blocks.back();
      b.ids.push_back(to_int(f[0]));
      std::vector<int> nodes;
      for (std::size_t i = 1; i < f.size(); ++i) nodes.push_back(to_int(f[i]));
      b.nodes.push_back(std::move(nodes));
    } else if (block == Block::nset) {
      auto& set = m.node_sets[nset];
      if (generate) {
        if (f.size() < 2) fail("first, last[, step]");
        const long long first = to_int(f[0]), last = to_int(f[1]), step = f.size() > 2 ? to_int(f[2]) : 1;
        if (step <= 0 || first > last || (last - first) / step > 100000000) fail("first <= last, step > 0, at most 1e8 ids");
        for (long long id = first; id <= last; id += step) set.push_back(static_cast<int>(id));
      } else {
        for (const auto& s : f) set.push_back(to_int(s));
      }
    }
  }
  if (points.empty()) throw_input_error(path.string(), "*NODE", "nodes", "none");
  m.points.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) m.points.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  for (const auto& b : m.blocks)
    for (const auto& e : b.nodes)
      for (int id : e)
        if (!m.row_of_node.count(id))
          throw_input_error(path.string(), "*ELEMENT " + b.elset, "elements on defined nodes", "node " + std::to_string(id));
  return m;
}

TriMesh shell_mesh(const AbaqusModel& model, const std::string& annulus_set, const std::string& free_edge_set,
                   std::vector<int>* model_rows) {
  TriMesh mesh;
  std::vector<int> index(model.points.rows(), -1), rows;
  std::vector<int> leaflet_of_triangle;
  auto node = [&](int id) {
    const int row = model.row_of_node.at(id);
    if (index[row] < 0) index[row] = static_cast<int>(rows.size()), rows.push_back(row);
    return index[row];
  };
  int leaflet = 0;
  for (const auto& b : model.blocks) {
    if (b.type.empty() || b.type[0] != 'S') continue;
    for (const auto& e : b.nodes) {
      if (e.size() == 3) {
        mesh.triangles.push_back({node(e[0]), node(e[1]), node(e[2])});
        leaflet_of_triangle.push_back(leaflet);
      } else if (e.size() == 4) {
        const int a = node(e[0]), b1 = node(e[1]), c = node(e[2]), d = node(e[3]);
        auto at = [&](int i) { return Vec3(model.points.row(rows[i]).transpose()); };
        if ((at(a) - at(c)).squaredNorm() <= (at(b1) - at(d)).squaredNorm()) {
          mesh.triangles.push_back({a, b1, c});
          mesh.triangles.push_back({a, c, d});
        } else {
          mesh.triangles.push_back({a, b1, d});
          mesh.triangles.push_back({b1, c, d});
        }
        leaflet_of_triangle.push_back(leaflet);
        leaflet_of_triangle.push_back(leaflet);
      }
    }
    ++leaflet;
  }
  if (mesh.triangles.empty()) throw InputError("abaqus model: expected shell elements (S3/S4), found none");
  mesh.points.resize(static_cast<Eigen::Index>(rows.size()), 3);
  for (std::size_t i = 0; i < rows.size(); ++i) mesh.points.row(static_cast<Eigen::Index>(i)) = model.points.row(rows[i]);
  mesh.fill_defaults();
  mesh.leaflet = leaflet_of_triangle;
  auto mark = [&](const std::string& set, auto apply) {
    const auto it = model.node_sets.find(upper(set));
    if (it == model.node_sets.end()) return;
    for (int id : it->second) {
      const auto row = model.row_of_node.find(id);
      if (row != model.row_of_node.end() && index[row->second] >= 0) apply(index[row->second]);
    }
  };
  mark(free_edge_set, [&](int i) { mesh.boundary[i] = BoundaryType::free_edge; });
  mark(annulus_set, [&](int i) {
    mesh.boundary[i] = BoundaryType::attached;
    mesh.roles[i] = NodeRole::fixed;
  });
  if (model_rows) *model_rows = rows;
  return mesh;
}

std::vector<std::pair<int, int>> line_elements(const AbaqusModel& model) {
  std::vector<std::pair<int, int>> out;
  for (const auto& b : model.blocks)
    if (b.type == "T3D2" || b.type == "B31" || b.type == "T3D3")
      for (const auto& e : b.nodes) out.emplace_back(model.row_of_node.at(e.front()), model.row_of_node.at(e.back()));
  return out;
}

}  // namespace valve
