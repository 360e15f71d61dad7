#include "valve/scene/calculix_deck.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>

#include "valve/core/error.hpp"

namespace valve {

namespace {

std::string number(double x) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.12g", x);  // ccx reads cards of at most 132 characters
  return buffer;
}

void refuse(const SceneConfig& scene, const std::string& key, const std::string& found) {
  throw_input_error(scene.file.string(), key,
                    "what a CalculiX membrane deck expresses (membrane_fe, iso_exponential with C1 = 0 and "
                    "compressible: true, fixed nodes, pressure)",
                    found);
}

}  // namespace

std::string calculix_deck(const SceneConfig& scene, const TriMesh& mesh, const CalculixDeckOptions& options) {
  if (scene.model != ModelKind::membrane_fe) refuse(scene, "model", "mass_spring");
  const MaterialConfig& m = scene.material;
  if (!m.iso_exponential) refuse(scene, "material.law", "a law other than iso_exponential");
  if (m.iso_exponential->C1 != 0) refuse(scene, "material.C1", number(m.iso_exponential->C1) + " MPa");
  if (!m.compressible) refuse(scene, "material.compressible", "false (CalculiX's NEO HOOKE keeps (J - 1)^2/D)");
  if (!scene.leaflet_materials.empty()) refuse(scene, "leaflet_materials", "a material per leaflet");
  if (scene.contact || scene.penalty_contact) refuse(scene, "contact", "contact");
  if (scene.chordae) refuse(scene, "chordae", "chordae");
  if (scene.bending) refuse(scene, "bending", "bending");
  if (scene.aortic_root) refuse(scene, "aortic_root", "an aortic root");
  if (scene.annulus_motion) refuse(scene, "annulus_motion", "annulus motion");
  if (scene.edge_loads) refuse(scene, "edge_loads", "edge loads");
  if (!scene.pressure) refuse(scene, "pressure", "no pressure");
  if (scene.fixed.planar || scene.fixed.pin_centre) refuse(scene, "fixed", "planar or pin_centre");

  std::ostringstream out;
  out << "** valve scene " << scene.file.string() << " as a CalculiX membrane deck (scene/calculix_deck.hpp)\n";
  out << "*NODE, NSET=NALL\n";
  for (int i = 0; i < mesh.num_nodes(); ++i)
    out << i + 1 << ", " << number(mesh.points(i, 0)) << ", " << number(mesh.points(i, 1)) << ", " << number(mesh.points(i, 2))
        << "\n";
  out << "*ELEMENT, TYPE=S3, ELSET=LEAFLETS\n";
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    const Tri& tri = mesh.triangles[t];
    out << t + 1 << ", " << tri[0] + 1 << ", " << tri[1] + 1 << ", " << tri[2] + 1 << "\n";
  }
  std::vector<int> fixed;
  for (int i = 0; i < mesh.num_nodes(); ++i)
    if (scene.fixed.use_node_roles && mesh.roles[i] == NodeRole::fixed) fixed.push_back(i);
  for (int i : scene.fixed.nodes) fixed.push_back(i);
  if (fixed.empty()) refuse(scene, "fixed", "no fixed node (the static problem would be singular)");
  out << "*NSET, NSET=FIXED\n";
  for (std::size_t k = 0; k < fixed.size(); ++k) out << fixed[k] + 1 << (k % 16 == 15 || k + 1 == fixed.size() ? "\n" : ", ");
  // NEO HOOKE: U = C10 (Ī1 − 3) + (J − 1)²/D1, i.e. C10 = C0/2.
  out << "*MATERIAL, NAME=LEAFLET\n*HYPERELASTIC, NEO HOOKE\n"
      << number(m.iso_exponential->C0 / 2) << ", " << number(m.iso_exponential->D) << "\n";
  out << "*SHELL SECTION, ELSET=LEAFLETS, MATERIAL=LEAFLET\n" << number(scene.thickness) << "\n";
  out << "*BOUNDARY\nFIXED, 1, 3\n";
  out << "*STEP, NLGEOM, INC=" << options.max_increments << "\n*STATIC\n"
      << number(options.initial_increment) << ", 1.0, " << number(options.minimum_increment) << ", "
      << number(options.initial_increment * 5) << "\n";
  // ccx's S3 shells move along their winding normal under a positive P (measured on the
  // clamped disk), the normal valve's pressure term uses.
  const double p = scene.pressure->along_normal ? scene.pressure->value : -scene.pressure->value;
  out << "*DLOAD\nLEAFLETS, P, " << number(p) << "\n";
  out << "*NODE PRINT, NSET=NALL\nU\n*END STEP\n";
  return out.str();
}

MatX3 read_calculix_displacements(const std::filesystem::path& dat_file, int num_nodes) {
  std::ifstream in(dat_file);
  if (!in) throw_input_error(dat_file.string(), "", "a CalculiX .dat file", "nothing there");
  MatX3 u = MatX3::Zero(num_nodes, 3);
  std::vector<char> seen;
  bool any = false, in_block = false;
  std::string line;
  while (std::getline(in, line)) {
    if (line.find("displacements (vx,vy,vz)") != std::string::npos) {
      in_block = true;
      any = true;
      u.setZero();
      seen.assign(num_nodes, 0);
      continue;
    }
    if (!in_block) continue;
    std::istringstream row(line);
    int node = 0;
    double x = 0, y = 0, z = 0;
    if (!(row >> node >> x >> y >> z)) {
      if (line.find_first_not_of(" \t\r") != std::string::npos) in_block = false;  // the next block's heading
      continue;
    }
    if (node < 1 || node > num_nodes)
      throw_input_error(dat_file.string(), "displacements", "nodes 1.." + std::to_string(num_nodes), "node " + std::to_string(node));
    u.row(node - 1) << x, y, z;
    seen[node - 1] = 1;
  }
  if (!any) throw_input_error(dat_file.string(), "displacements", "a displacements (vx,vy,vz) block", "none");
  for (int i = 0; i < num_nodes; ++i)
    if (!seen[i]) throw_input_error(dat_file.string(), "displacements", "every node", "node " + std::to_string(i + 1) + " missing");
  return u;
}

}  // namespace valve
