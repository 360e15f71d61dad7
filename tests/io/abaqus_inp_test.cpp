// The Abaqus deck reader on a hand-written two-quad model: every number below is read off
// tests/io/data/two_quads.inp.
#include <catch2/catch.hpp>

#include "valve/core/error.hpp"
#include "valve/io/abaqus_inp.hpp"

using namespace valve;

TEST_CASE("an Abaqus deck gives nodes, shells as triangles, trusses and node sets", "[io][abaqus]") {
  const AbaqusModel m = read_abaqus_inp(VALVE_TEST_DATA_DIR "/two_quads.inp");
  REQUIRE(m.points.rows() == 7);
  CHECK(m.points(m.row_of_node.at(10), 2) == -5.0);
  REQUIRE(m.blocks.size() == 3);
  CHECK(m.blocks[0].type == "S4R");
  CHECK(m.node_sets.at("FREE_EDGE_NODES") == std::vector<int>{4, 5, 6});  // GENERATE
  CHECK(m.node_sets.at("ANNULAR_NODES") == std::vector<int>{1, 2, 3});
  CHECK(m.node_sets.at("LEAFLET_NODES").size() == 6);

  std::vector<int> rows;
  const TriMesh mesh = shell_mesh(m, "Annular_Nodes", "Free_Edge_Nodes", &rows);
  CHECK(mesh.num_nodes() == 6);  // the truss node is not a shell node
  CHECK(mesh.num_triangles() == 4);
  CHECK(mesh.leaflet == std::vector<int>{0, 0, 1, 1});
  double area = 0;
  for (const Tri& t : mesh.triangles) {
    area += triangle_area(mesh.points, t);
    CHECK(triangle_normal(mesh.points, t).z() > 0.99);  // the quads' orientation kept
  }
  CHECK(area == Approx(2.0));
  int fixed = 0, free_edge = 0;
  for (int i = 0; i < mesh.num_nodes(); ++i) {
    fixed += mesh.roles[i] == NodeRole::fixed && mesh.boundary[i] == BoundaryType::attached;
    free_edge += mesh.boundary[i] == BoundaryType::free_edge;
    CHECK(mesh.points.row(i) == m.points.row(rows[i]));
  }
  CHECK(fixed == 3);
  CHECK(free_edge == 3);

  // Element 2's distribution vector (0, 1, 0.5) projected onto its plane z = 0 is +y; element 1
  // has none and keeps the default (its first edge, +x).
  CHECK(mesh.fiber.row(2).y() == Approx(1.0));
  CHECK(mesh.fiber.row(3).y() == Approx(1.0));
  CHECK(mesh.fiber.row(0).x() == Approx(1.0));
  REQUIRE(m.sections.size() == 3);
  CHECK(m.sections[0].kind == "SOLID");
  CHECK(m.sections[0].value == 0.25);
  CHECK(m.sections[1].kind == "SHELL");
  CHECK(m.sections[1].material == "VUANISO_ISO_A");
  CHECK(m.sections[1].value == 0.65);
  CHECK(m.element_sets.at("CHORDAE") == std::vector<int>{3});
  // Nodes 4-6 by their set (ENCASTRE), node 2's symmetry condition and node 3's rotations
  // hold no full translation and are not recorded.
  REQUIRE(m.boundary.size() == 6);
  for (int id : {4, 5, 6}) CHECK(m.boundary.at(id).dof_mask == 7);
  CHECK(m.boundary.at(4).displacement == Vec3::Zero());
  CHECK(m.boundary.count(2) == 0);
  CHECK(m.boundary.at(3).dof_mask == 0);
  CHECK(m.boundary.at(1).dof_mask == 7);
  CHECK(m.boundary.at(1).displacement == Vec3(0.5, -0.25, 0.125));
  CHECK(m.boundary.at(10).dof_mask == 7);
  CHECK(m.boundary.at(10).displacement == Vec3::Zero());

  const auto lines = line_elements(m);
  REQUIRE(lines.size() == 1);
  CHECK(m.node_ids[lines[0].first] == 10);
  CHECK(m.node_ids[lines[0].second] == 1);
}

TEST_CASE("a deck's materials become valve's laws with the subroutine's property order", "[io][abaqus]") {
  const AbaqusModel m = read_abaqus_inp(VALVE_TEST_DATA_DIR "/two_quads.inp");
  REQUIRE(m.materials.size() == 3);
  CHECK(m.materials.at("CHORDAE").options.size() == 2);  // *Density, *Hyperelastic

  const nlohmann::json leaflets = leaflet_materials_json(m, "two_quads.inp");
  REQUIRE(leaflets.size() == 2);
  CHECK(leaflets[0]["leaflets"] == nlohmann::json{0});
  CHECK(leaflets[0]["thickness"] == "0.65 mm");
  const nlohmann::json& iso = leaflets[0]["material"];
  CHECK(iso["law"] == "iso_exponential");  // VUANISO_ISO: C0, D, C1, C2
  CHECK(iso["C0"] == "0.001 MPa");
  CHECK(iso["D"] == "20.06689 1/MPa");
  CHECK(iso["C1"] == "0.000124 MPa");
  CHECK(iso["C2"].get<double>() == 4.568202);
  CHECK(iso["density"] == "0.001 g/mm^3");  // 1e-9 tonne/mm³
  CHECK(iso["source"].get<std::string>().find("VUANISO_ISO_A") != std::string::npos);
  const nlohmann::json& hgo = leaflets[1]["material"];
  CHECK(hgo["law"] == "hgo");  // VUANISO_HGO: C10, D, k1, k2, kappa, C01 over two data lines
  CHECK(hgo["C10"] == "0.002 MPa");
  CHECK(hgo["D"] == "10 1/MPa");
  CHECK(hgo["k1"] == "0.0003 MPa");
  CHECK(hgo["k2"].get<double>() == 12.0);
  CHECK(hgo["kappa"].get<double>() == 0.05);
  CHECK(hgo["C01"].get<double>() == 15.0);

  std::vector<int> rows;
  const TriMesh mesh = shell_mesh(m, "Annular_Nodes", "Free_Edge_Nodes", &rows);
  const ChordaeNetwork net = truss_chordae(m, rows, mesh, "two_quads.inp");
  REQUIRE(net.segments.size() == 1);
  CHECK(net.segments[0].material == "Chordae");
  CHECK(net.segments[0].area == 0.25);
  const nlohmann::json& ogden = net.materials.at("Chordae");
  CHECK(ogden["law"] == "ogden");  // μ1, α1, μ2, α2, D1, D2
  CHECK(ogden["mu"] == nlohmann::json{"1.5 MPa", "0.5 MPa"});
  CHECK(ogden["alpha"] == nlohmann::json{20.0, 2.0});
  CHECK(ogden["D"] == nlohmann::json{"0.0001 1/MPa", "0 1/MPa"});
}

TEST_CASE("a deck material valve does not model is refused by name", "[io][abaqus]") {
  const AbaqusModel leaflet = read_abaqus_inp(VALVE_TEST_DATA_DIR "/unmodelled_leaflet_material.inp");
  CHECK_THROWS_WITH(leaflet_materials_json(leaflet, "deck.inp"),
                    Catch::Contains("deck.inp") && Catch::Contains("VUANISO_ISO_A") && Catch::Contains("MOONEY-RIVLIN"));
  const AbaqusModel chord = read_abaqus_inp(VALVE_TEST_DATA_DIR "/unmodelled_chord_material.inp");
  std::vector<int> rows;
  const TriMesh mesh = shell_mesh(chord, "Annular_Nodes", "Free_Edge_Nodes", &rows);
  CHECK_THROWS_WITH(truss_chordae(chord, rows, mesh, "deck.inp"),
                    Catch::Contains("name=Chordae") && Catch::Contains("ARRUDA-BOYCE"));
}

TEST_CASE("a broken deck names the file and line", "[io][abaqus]") {
  CHECK_THROWS_WITH(read_abaqus_inp(VALVE_TEST_DATA_DIR "/no_such.inp"), Catch::Contains("no_such.inp"));
  CHECK_THROWS_WITH(read_abaqus_inp(VALVE_TEST_DATA_DIR "/bad_node.inp"), Catch::Contains("line 3"));
  // A *Boundary on a node set the deck never defines.
  CHECK_THROWS_WITH(read_abaqus_inp(VALVE_TEST_DATA_DIR "/bad_boundary.inp"),
                    Catch::Contains("line 4") && Catch::Contains("node set"));
}
