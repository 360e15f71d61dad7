// The CalculiX deck of a scene: the cards a clamped sheet needs, the material as NEO HOOKE
// with C10 = C0/2, what a deck cannot express refused by key, and displacements read back
// from a ccx .dat file (its last block; a missing node is an error).
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "valve/core/error.hpp"
#include "valve/mesh/generators.hpp"
#include "valve/scene/calculix_deck.hpp"

using namespace valve;

namespace {
SceneConfig neo_hookean_scene(const json& patch = json::object()) {
  json j{{"mesh", "unused.vtp"},
         {"model", "membrane_fe"},
         {"material", {{"law", "iso_exponential"}, {"C0", "0.4 MPa"}, {"D", "0.05 1/MPa"}, {"compressible", true}}},
         {"thickness", "0.05 mm"},
         {"pressure", {{"value", "1 kPa"}, {"direction", "against_normal"}}}};
  j.merge_patch(patch);
  return parse_scene(j, "s.json", ".");
}
}  // namespace

TEST_CASE("a clamped neo-Hookean sheet becomes a CalculiX deck", "[scene][calculix]") {
  DiskOptions o;
  o.mesh.target_triangles = 40;
  const TriMesh disk = generate_clamped_disk(o);
  const std::string deck = calculix_deck(neo_hookean_scene(), disk);
  CHECK(deck.find("*ELEMENT, TYPE=S3, ELSET=LEAFLETS") != std::string::npos);
  CHECK(deck.find("*HYPERELASTIC, NEO HOOKE\n0.2, 0.05\n") != std::string::npos);  // C10 = C0/2, D1 = D
  CHECK(deck.find("*SHELL SECTION, ELSET=LEAFLETS, MATERIAL=LEAFLET\n0.05\n") != std::string::npos);
  CHECK(deck.find("*STEP, NLGEOM") != std::string::npos);
  CHECK(deck.find("LEAFLETS, P, -0.001\n") != std::string::npos);  // against the normal: negative P
  CHECK(deck.find("FIXED, 1, 3") != std::string::npos);
  int fixed = 0;
  for (NodeRole r : disk.roles) fixed += r == NodeRole::fixed;
  const auto nset = deck.find("*NSET, NSET=FIXED\n"), material = deck.find("*MATERIAL");
  const std::string ids = deck.substr(nset + 18, material - nset - 18);
  CHECK(std::count(ids.begin(), ids.end(), ',') + std::count(ids.begin(), ids.end(), '\n') == fixed);
}

TEST_CASE("what a CalculiX deck cannot express is refused by key", "[scene][calculix]") {
  DiskOptions o;
  o.mesh.target_triangles = 40;
  const TriMesh disk = generate_clamped_disk(o);
  CHECK_THROWS_WITH(calculix_deck(neo_hookean_scene({{"model", "mass_spring"}}), disk), Catch::Contains("model"));
  CHECK_THROWS_WITH(calculix_deck(neo_hookean_scene({{"material", {{"compressible", false}}}}), disk),
                    Catch::Contains("material.compressible"));
  CHECK_THROWS_WITH(calculix_deck(neo_hookean_scene({{"material", {{"C1", "1 kPa"}, {"C2", 3}}}}), disk),
                    Catch::Contains("material.C1"));
  CHECK_THROWS_WITH(calculix_deck(neo_hookean_scene({{"bending", {{"modulus", "1 MPa"}}}}), disk), Catch::Contains("bending"));
  CHECK_THROWS_WITH(calculix_deck(neo_hookean_scene({{"contact", {{"model", "penalty"}}}}), disk), Catch::Contains("contact"));
}

TEST_CASE("displacements come from the last block of a ccx .dat file", "[scene][calculix]") {
  namespace fs = std::filesystem;
  const fs::path dat = fs::temp_directory_path() / "valve_calculix_test.dat";
  std::ofstream(dat) << "\n displacements (vx,vy,vz) for set NALL and time  0.5000000E+00\n\n"
                        "         1  1.0E+00  0.0E+00  0.0E+00\n         2  0.0E+00  2.0E+00  0.0E+00\n\n"
                        " displacements (vx,vy,vz) for set NALL and time  0.1000000E+01\n\n"
                        "         1  0.000000E+00  0.000000E+00 -1.500000E-01\n"
                        "         2  2.500000E-01  0.000000E+00  0.000000E+00\n";
  const MatX3 u = read_calculix_displacements(dat, 2);
  CHECK(u(0, 2) == Approx(-0.15));
  CHECK(u(1, 0) == Approx(0.25));
  CHECK(u(1, 1) == 0);
  CHECK_THROWS_WITH(read_calculix_displacements(dat, 3), Catch::Contains("node 3 missing"));
  fs::remove(dat);
}
