#include "valve/io/abaqus_inp.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
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
  enum class Block { none, node, element, nset, elset, distribution, section, material_option, boundary } block = Block::none;
  std::string nset, elset;
  AbaqusModel::Material* material = nullptr;  // the *Material whose options follow
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
      if (used != s.size() || !std::isfinite(v)) fail("finite numbers");
      return v;
    } catch (const std::logic_error&) {
      fail("finite numbers");
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
      // A material's options follow its *Material line; any other keyword ends it.
      static const std::vector<std::string> kMaterialOptions{
          "*DENSITY", "*ELASTIC", "*HYPERELASTIC", "*ANISOTROPIC HYPERELASTIC", "*HYPERFOAM", "*VISCOELASTIC",
          "*PLASTIC", "*USER MATERIAL", "*DEPVAR", "*TRANSVERSE SHEAR", "*DAMPING", "*EXPANSION", "*MULLINS EFFECT"};
      if (material && std::find(kMaterialOptions.begin(), kMaterialOptions.end(), keyword) != kMaterialOptions.end()) {
        AbaqusModel::MaterialOption option;
        for (const auto& w : words) option.words.push_back(upper(w));
        option.line = number;
        material->options.push_back(option);
        block = Block::material_option;
        continue;
      }
      material = nullptr;
      if (keyword == "*NODE") {
        block = Block::node;
        const std::string set = upper(parameter(words, "NSET"));
        if (!set.empty()) nset = set, m.node_sets[nset];  // filled as nodes come
        else nset.clear();
      } else if (keyword == "*ELEMENT") {
        block = Block::element;
        m.blocks.push_back({upper(parameter(words, "TYPE")), parameter(words, "ELSET"), {}, {}});
        elset = upper(parameter(words, "ELSET"));
      } else if (keyword == "*NSET") {
        block = Block::nset;
        nset = upper(parameter(words, "NSET"));
        generate = has_word(words, "GENERATE");
        m.node_sets[nset];
      } else if (keyword == "*ELSET") {
        block = Block::elset;
        elset = upper(parameter(words, "ELSET"));
        generate = has_word(words, "GENERATE");
        m.element_sets[elset];
      } else if (keyword == "*DISTRIBUTION" && upper(parameter(words, "LOCATION")) == "ELEMENT") {
        block = Block::distribution;
      } else if (keyword == "*SOLID SECTION" || keyword == "*SHELL SECTION") {
        block = Block::section;
        m.sections.push_back({keyword == "*SHELL SECTION" ? "SHELL" : "SOLID", parameter(words, "ELSET"),
                              parameter(words, "MATERIAL"), 0.0});
      } else if (keyword == "*MATERIAL") {
        const std::string name = parameter(words, "NAME");
        if (name.empty()) fail("*Material, name=NAME");
        material = &m.materials[upper(name)];
        material->name = name;
        material->line = number;
      } else if (keyword == "*BOUNDARY") {
        block = Block::boundary;
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
      if (!elset.empty()) m.element_sets[elset].push_back(b.ids.back());
      std::vector<int> nodes;
      for (std::size_t i = 1; i < f.size(); ++i) nodes.push_back(to_int(f[i]));
      b.nodes.push_back(std::move(nodes));
    } else if (block == Block::distribution) {
      if (!f.empty() && f[0].empty()) continue;  // ", a, b": the default, for elements not listed
      if (f.size() < 4) fail("a distribution line: element id, a1, a2, a3[, b1, b2, b3]");
      m.element_direction[to_int(f[0])] = Vec3(to_double(f[1]), to_double(f[2]), to_double(f[3]));
    } else if (block == Block::section) {
      if (!f.empty() && !f[0].empty()) m.sections.back().value = to_double(f[0]);
      block = Block::none;  // one data line
    } else if (block == Block::material_option) {
      for (const auto& s : f)
        if (!s.empty()) material->options.back().data.push_back(to_double(s));
    } else if (block == Block::boundary) {
      // "node, first dof[, last dof[, value]]" or "node, ENCASTRE|PINNED"; node is an id, a
      // node set, or either prefixed by "Instance.". Rotations (dofs 4-6) and other named
      // types (symmetry conditions) hold no full translation and are not recorded.
      if (f.size() < 2) fail("a boundary line: node, first dof[, last dof[, value]]");
      const auto dot = f[0].rfind('.');
      const std::string ref = dot == std::string::npos ? f[0] : f[0].substr(dot + 1);
      std::vector<int> ids;
      if (!ref.empty() && std::all_of(ref.begin(), ref.end(), [](unsigned char c) { return std::isdigit(c); })) {
        ids.push_back(to_int(ref));
      } else if (const auto set = m.node_sets.find(upper(ref)); set != m.node_sets.end()) {
        ids = set->second;
      } else {
        fail("a node id or a node set defined before the *Boundary");
      }
      int first = 1, last = 3;
      double value = 0.0;
      const std::string type = upper(f[1]);
      if (type != "ENCASTRE" && type != "PINNED") {
        if (!std::isdigit(static_cast<unsigned char>(f[1].empty() ? 'x' : f[1][0]))) continue;  // XSYMM etc.
        first = to_int(f[1]);
        last = f.size() > 2 && !f[2].empty() ? to_int(f[2]) : first;
        value = f.size() > 3 ? to_double(f[3]) : 0.0;
        if (first < 1 || first > last) fail("dofs first <= last, from 1");
      }
      for (int id : ids) {
        auto& b = m.boundary[id];
        for (int k = first; k <= std::min(last, 3); ++k) b.displacement[k - 1] = value, b.dof_mask |= 1 << (k - 1);
      }
    } else if (block == Block::nset || block == Block::elset) {
      auto& set = block == Block::nset ? m.node_sets[nset] : m.element_sets[elset];
      if (generate) {
        if (f.size() < 2) fail("first, last[, step]");
        const long long first = to_int(f[0]), last = to_int(f[1]), step = f.size() > 2 ? to_int(f[2]) : 1;
        if (step <= 0 || first > last || (last - first) / step > 100000000) fail("first <= last, step > 0, at most 1e8 ids");
        for (long long id = first; id <= last; id += step) set.push_back(static_cast<int>(id));
      } else {
        // Ids, or the names of sets defined before (an *Elset of other elsets).
        const auto& sets = block == Block::nset ? m.node_sets : m.element_sets;
        for (const auto& s : f) {
          const auto named = sets.find(upper(s));
          if (!s.empty() && !std::isdigit(static_cast<unsigned char>(s[0])) && s[0] != '-' && named != sets.end())
            set.insert(set.end(), named->second.begin(), named->second.end());
          else
            set.push_back(to_int(s));
        }
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
  std::vector<const Vec3*> direction_of_triangle;  // the element's *Distribution vector, if any
  auto node = [&](int id) {
    const int row = model.row_of_node.at(id);
    if (index[row] < 0) index[row] = static_cast<int>(rows.size()), rows.push_back(row);
    return index[row];
  };
  int leaflet = 0;
  for (const auto& b : model.blocks) {
    if (b.type.empty() || b.type[0] != 'S') continue;
    for (std::size_t k = 0; k < b.nodes.size(); ++k) {
      const auto& e = b.nodes[k];
      const auto dir = model.element_direction.find(b.ids[k]);
      const Vec3* direction = dir == model.element_direction.end() ? nullptr : &dir->second;
      if (e.size() == 3) {
        mesh.triangles.push_back({node(e[0]), node(e[1]), node(e[2])});
        leaflet_of_triangle.push_back(leaflet);
        direction_of_triangle.push_back(direction);
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
        leaflet_of_triangle.insert(leaflet_of_triangle.end(), 2, leaflet);
        direction_of_triangle.insert(direction_of_triangle.end(), 2, direction);
      }
    }
    ++leaflet;
  }
  if (mesh.triangles.empty()) throw InputError("abaqus model: expected shell elements (S3/S4), found none");
  mesh.points.resize(static_cast<Eigen::Index>(rows.size()), 3);
  for (std::size_t i = 0; i < rows.size(); ++i) mesh.points.row(static_cast<Eigen::Index>(i)) = model.points.row(rows[i]);
  mesh.fill_defaults();
  mesh.leaflet = leaflet_of_triangle;
  // Abaqus projects a shell's local 1-direction onto the shell surface.
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    if (!direction_of_triangle[t]) continue;
    const Vec3 n = triangle_normal(mesh.points, mesh.triangles[t]);
    const Vec3 a = *direction_of_triangle[t] - direction_of_triangle[t]->dot(n) * n;
    if (a.norm() > 1e-6 * direction_of_triangle[t]->norm()) mesh.fiber.row(t) = a.normalized().transpose();
  }
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

namespace {
bool is_line_element(const std::string& type) { return type == "T3D2" || type == "B31" || type == "T3D3"; }
}  // namespace

std::vector<std::pair<int, int>> line_elements(const AbaqusModel& model) {
  std::vector<std::pair<int, int>> out;
  for (const auto& b : model.blocks)
    if (is_line_element(b.type))
      for (const auto& e : b.nodes) out.emplace_back(model.row_of_node.at(e.front()), model.row_of_node.at(e.back()));
  return out;
}

namespace {

std::string quote_numbers(const std::vector<double>& data) {
  std::string out;
  for (double v : data) out += (out.empty() ? "" : ", ") + format_number(v);
  return out;
}

std::string option_text(const AbaqusModel::MaterialOption& o) {
  std::string text;
  for (const auto& w : o.words) text += (text.empty() ? "" : ", ") + w;
  return text;
}

// "DECK *Material, name=NAME (line N): OPTION: numbers": the line a preset's source quotes.
std::string source_line(const AbaqusModel::Material& m, const AbaqusModel::MaterialOption& o, const std::string& file) {
  return file + " *Material, name=" + m.name + " (line " + std::to_string(m.line) + "): " + option_text(o) + ": " +
         quote_numbers(o.data) + " (units mm, tonne, s, MPa)";
}

const AbaqusModel::MaterialOption* find_option(const AbaqusModel::Material& m, const std::string& keyword) {
  for (const auto& o : m.options)
    if (o.keyword() == keyword) return &o;
  return nullptr;
}

// The *Material that a section names; InputError naming the section when the deck has none.
const AbaqusModel::Material& section_material(const AbaqusModel& model, const AbaqusModel::Section& section,
                                              const std::string& file) {
  const auto material = model.materials.find(upper(section.material));
  if (material == model.materials.end())
    throw_input_error(file, "*" + std::string(section.kind == "SHELL" ? "Shell" : "Solid") + " Section, elset=" + section.elset,
                      "a *Material named " + section.material, "none");
  return material->second;
}

std::string mpa(double v) { return format_number(v) + " MPa"; }
std::string per_mpa(double v) { return format_number(v) + " 1/MPa"; }

[[noreturn]] void not_modelled(const AbaqusModel::Material& m, const std::string& file, const std::string& expected) {
  std::string found;
  for (const auto& o : m.options)
    if (o.keyword() != "*DENSITY" && o.keyword() != "*DEPVAR" && o.keyword() != "*TRANSVERSE SHEAR" &&
        o.keyword() != "*DAMPING")
      found += (found.empty() ? "" : "; ") + option_text(o);
  throw_input_error(file, "*Material, name=" + m.name + " (line " + std::to_string(m.line) + ")", expected,
                    found.empty() ? "no constitutive option" : found);
}

void need_values(const AbaqusModel::Material& m, const AbaqusModel::MaterialOption& o, std::size_t count,
                 const std::string& file) {
  if (o.data.size() < count)
    throw_input_error(file, "*Material, name=" + m.name + " " + option_text(o) + " (line " + std::to_string(o.line) + ")",
                      std::to_string(count) + " values", std::to_string(o.data.size()));
}

}  // namespace

nlohmann::json leaflet_material_json(const AbaqusModel::Material& m, const std::string& file) {
  const std::string expected =
      "a leaflet law valve models (*Anisotropic Hyperelastic, USER named VUANISO_ISO* or VUANISO_HGO*, or "
      "*Hyperelastic, NEO HOOKE)";
  nlohmann::json j = {{"name", m.name}};
  const std::string name = upper(m.name);
  if (const auto* o = find_option(m, "*ANISOTROPIC HYPERELASTIC"); o && has_word(o->words, "USER")) {
    j["source"] = source_line(m, *o, file) + "; the branch of Leaflet_Material.f its name selects";
    if (name.rfind("VUANISO_ISO", 0) == 0) {
      need_values(m, *o, 4, file);
      j["law"] = "iso_exponential";
      j["C0"] = mpa(o->data[0]);
      j["D"] = per_mpa(o->data[1]);
      j["C1"] = mpa(o->data[2]);
      j["C2"] = o->data[3];
    } else if (name.rfind("VUANISO_HGO", 0) == 0) {
      need_values(m, *o, 6, file);
      j["law"] = "hgo";
      j["C10"] = mpa(o->data[0]);
      j["D"] = per_mpa(o->data[1]);
      j["k1"] = mpa(o->data[2]);
      j["k2"] = o->data[3];
      j["kappa"] = o->data[4];
      j["C01"] = o->data[5];
    } else {
      not_modelled(m, file, expected);
    }
  } else if (const auto* h = find_option(m, "*HYPERELASTIC"); h && has_word(h->words, "NEO HOOKE")) {
    need_values(m, *h, 1, file);
    j["source"] = source_line(m, *h, file) + "; NEO HOOKE C10 (Ī1 − 3) is C0/2 (Ī1 − 3) with C0 = 2 C10";
    j["law"] = "iso_exponential";
    j["C0"] = mpa(2 * h->data[0]);
    j["D"] = per_mpa(h->data.size() > 1 ? h->data[1] : 0.0);
  } else {
    not_modelled(m, file, expected);
  }
  if (const auto* d = find_option(m, "*DENSITY"); d && !d->data.empty())
    j["density"] = format_number(d->data[0] * 1e6) + " g/mm^3";  // tonne/mm³ -> g/mm³
  return j;
}

nlohmann::json chord_law_json(const AbaqusModel::Material& m, const std::string& file) {
  const std::string expected = "a chord law valve models (*Hyperelastic, OGDEN or NEO HOOKE, or *Elastic)";
  nlohmann::json j;
  if (const auto* h = find_option(m, "*HYPERELASTIC"); h && has_word(h->words, "OGDEN")) {
    const std::string n_text = parameter(h->words, "N");
    const int n = n_text.empty() ? 1 : std::atoi(n_text.c_str());
    if (n < 1 || n > 3)
      throw_input_error(file, "*Material, name=" + m.name + " " + option_text(*h), "OGDEN with N = 1..3", "N=" + n_text);
    need_values(m, *h, 3 * n, file);
    j["source"] = source_line(m, *h, file);
    j["law"] = "ogden";
    j["mu"] = nlohmann::json::array();
    j["alpha"] = nlohmann::json::array();
    j["D"] = nlohmann::json::array();
    for (int k = 0; k < n; ++k) {
      j["mu"].push_back(mpa(h->data[2 * k]));
      j["alpha"].push_back(h->data[2 * k + 1]);
      j["D"].push_back(per_mpa(h->data[2 * n + k]));
    }
  } else if (h && has_word(h->words, "NEO HOOKE")) {
    need_values(m, *h, 1, file);
    j["source"] = source_line(m, *h, file) + "; NEO HOOKE is Ogden N = 1 with mu = 2 C10, alpha = 2";
    j["law"] = "ogden";
    j["mu"] = {mpa(2 * h->data[0])};
    j["alpha"] = {2.0};
    j["D"] = {per_mpa(h->data.size() > 1 ? h->data[1] : 0.0)};
  } else if (const auto* e = find_option(m, "*ELASTIC");
             e && !has_word(e->words, "TYPE=ENGINEERING CONSTANTS") && !has_word(e->words, "TYPE=ORTHOTROPIC")) {
    need_values(m, *e, 1, file);
    j["source"] = source_line(m, *e, file);
    j["law"] = "linear";
    j["youngs_modulus"] = mpa(e->data[0]);
  } else {
    not_modelled(m, file, expected);
  }
  return j;
}

nlohmann::json leaflet_materials_json(const AbaqusModel& model, const std::string& file) {
  nlohmann::json list = nlohmann::json::array();
  bool any = false;
  for (const auto& s : model.sections) any = any || s.kind == "SHELL";
  if (!any) return list;
  int leaflet = 0;
  for (const auto& b : model.blocks) {
    if (b.type.empty() || b.type[0] != 'S') continue;
    const AbaqusModel::Section* section = nullptr;
    for (const auto& s : model.sections) {
      if (s.kind != "SHELL") continue;
      const auto set = model.element_sets.find(upper(s.elset));
      if (upper(s.elset) == upper(b.elset) ||
          (set != model.element_sets.end() && !b.ids.empty() &&
           std::find(set->second.begin(), set->second.end(), b.ids.front()) != set->second.end()))
        section = &s;
    }
    if (!section)
      throw_input_error(file, "*Element, elset=" + b.elset, "a *Shell Section for every shell element block", "none");
    list.push_back({{"leaflets", {leaflet}},
                    {"material", leaflet_material_json(section_material(model, *section, file), file)},
                    {"thickness", format_number(section->value) + " mm"}});
    ++leaflet;
  }
  return list;
}

ChordaeNetwork truss_chordae(const AbaqusModel& model, const std::vector<int>& model_rows, const TriMesh& leaflets,
                             const std::string& file, double* max_tip_motion_mm) {
  std::vector<int> mesh_node(model.points.rows(), -1), point_of_row(model.points.rows(), -1);
  for (std::size_t i = 0; i < model_rows.size(); ++i) mesh_node[model_rows[i]] = static_cast<int>(i);
  ChordaeNetwork net;
  double tip_motion = 0;
  auto point = [&](int row) {
    if (point_of_row[row] >= 0) return point_of_row[row];
    ChordPoint p;
    p.position = model.points.row(row).transpose();
    const int id = model.node_ids[row];
    p.name = "node " + std::to_string(id);
    const auto held = model.boundary.find(id);
    if (mesh_node[row] >= 0) {
      p.kind = ChordPointKind::insertion;
      p.mesh_node = mesh_node[row];
    } else if (held != model.boundary.end() && held->second.dof_mask == 7) {
      p.kind = ChordPointKind::papillary_tip;
      tip_motion = std::max(tip_motion, held->second.displacement.norm());
    } else {
      p.kind = ChordPointKind::branch;
    }
    point_of_row[row] = static_cast<int>(net.points.size());
    net.points.push_back(p);
    return point_of_row[row];
  };
  auto on_free_edge = [&](int p) {
    return net.points[p].kind == ChordPointKind::insertion && leaflets.boundary[net.points[p].mesh_node] == BoundaryType::free_edge;
  };
  // The *Solid Section of each truss element, through its elset.
  std::unordered_map<int, const AbaqusModel::Section*> section_of;
  double area_sum = 0;
  int area_count = 0;
  for (const auto& s : model.sections) {
    if (s.kind != "SOLID") continue;
    area_sum += s.value, ++area_count;
    const auto set = model.element_sets.find(upper(s.elset));
    if (set != model.element_sets.end())
      for (int id : set->second) section_of[id] = &s;
  }
  for (const auto& b : model.blocks) {
    if (!is_line_element(b.type)) continue;
    for (std::size_t k = 0; k < b.nodes.size(); ++k) {
      ChordSegment seg;
      seg.from = point(model.row_of_node.at(b.nodes[k].front()));
      seg.to = point(model.row_of_node.at(b.nodes[k].back()));
      seg.type = on_free_edge(seg.from) || on_free_edge(seg.to) ? ChordType::primary : ChordType::secondary;
      if (const auto it = section_of.find(b.ids[k]); it != section_of.end()) {
        const AbaqusModel::Section& s = *it->second;
        seg.area = s.value;
        const AbaqusModel::Material& material = section_material(model, s, file);
        seg.material = material.name;
        if (!net.materials.count(seg.material)) net.materials[seg.material] = chord_law_json(material, file);
      }
      net.segments.push_back(seg);
    }
  }
  if (area_count > 0) net.diameter = std::sqrt(4 * (area_sum / area_count) / M_PI);
  if (max_tip_motion_mm) *max_tip_motion_mm = tip_motion;
  return net;
}

}  // namespace valve
