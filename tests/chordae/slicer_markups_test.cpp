// Landmark curves written for 3D Slicer's Markups module: read back as plain JSON and checked
// against the markups schema (v1.0.3: "@schema", markup "type" from its enum, LPS/RAS,
// control point positions) and against the nodes marked by hand on a small mesh.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "support/test_meshes.hpp"
#include "valve/chordae/slicer_markups.hpp"

namespace fs = std::filesystem;
using namespace valve;

TEST_CASE("valve_landmark_curves and write_slicer_curves: annulus, free edge, coaptation line", "[slicer_markups]") {
  // 3x3 grid, nodes 3 j + i. Boundary loop 0 1 2 5 8 7 6 3: node 1 is the free edge between the
  // attached corners 0 and 2; 3, 5, 6, 7, 8 are attached and fixed.
  TriMesh m = test::grid_mesh(2.0);
  for (int n : {0, 2, 3, 5, 6, 7, 8}) m.boundary[n] = BoundaryType::attached, m.roles[n] = NodeRole::fixed;
  m.boundary[1] = BoundaryType::free_edge;
  const VecX x = flatten(m.points);
  const std::vector<int> coapting = {1, 1, 0, 0, 0, 0, 0, 0, 0};
  const auto curves = valve_landmark_curves(m, x, &coapting);
  const fs::path file = fs::temp_directory_path() / "valve_markups_test" / "landmarks.mrk.json";
  fs::create_directories(file.parent_path());
  write_slicer_curves(file, curves);

  nlohmann::json doc;
  std::ifstream(file) >> doc;
  REQUIRE(doc["@schema"].is_string());
  CHECK(doc["@schema"].get<std::string>().find("markups-schema-v1.0.3.json") != std::string::npos);
  REQUIRE(doc["markups"].size() == 3);
  const std::set<std::string> types = {"Fiducial", "Line", "Angle", "Curve", "ClosedCurve", "Plane", "ROI"};
  auto positions = [](const nlohmann::json& mk) {
    std::vector<Vec3> p;
    for (const auto& cp : mk["controlPoints"]) p.emplace_back(cp["position"][0], cp["position"][1], cp["position"][2]);
    return p;
  };
  auto node = [&](int n) { return Vec3(m.points.row(n).transpose()); };
  for (const auto& mk : doc["markups"]) {
    CHECK(types.count(mk["type"].get<std::string>()) == 1);
    CHECK(mk["coordinateSystem"] == "LPS");
    CHECK(mk["coordinateUnits"] == "mm");
  }
  const auto& annulus = doc["markups"][0];
  CHECK(annulus["name"] == "annulus");
  // The attachment is an arc from corner 2 round to corner 0, not closed across the free edge.
  CHECK(annulus["type"] == "Curve");
  const auto ring = positions(annulus);
  REQUIRE(ring.size() == 7);
  for (int n : {0, 2, 3, 5, 6, 7, 8})
    CHECK(std::count_if(ring.begin(), ring.end(), [&](const Vec3& p) { return (p - node(n)).norm() < 1e-12; }) == 1);
  CHECK(std::min((ring.front() - node(2)).norm(), (ring.front() - node(0)).norm()) < 1e-12);
  CHECK(std::min((ring.back() - node(2)).norm(), (ring.back() - node(0)).norm()) < 1e-12);
  for (std::size_t k = 1; k < ring.size(); ++k) CHECK((ring[k] - ring[k - 1]).norm() == Approx(1.0));  // boundary neighbours

  const auto& edge = doc["markups"][1];
  CHECK(edge["name"] == "free edge");
  CHECK(edge["type"] == "Curve");
  const auto e = positions(edge);
  REQUIRE(e.size() == 3);
  CHECK((e[1] - node(1)).norm() < 1e-12);
  CHECK(std::min((e[0] - node(0)).norm(), (e[0] - node(2)).norm()) < 1e-12);

  const auto& line = doc["markups"][2];
  CHECK(line["name"] == "coaptation line");
  const auto c = positions(line);
  REQUIRE(c.size() == 2);
  CHECK(std::min((c[0] - node(0)).norm(), (c[1] - node(0)).norm()) < 1e-12);
  CHECK(std::min((c[0] - node(1)).norm(), (c[1] - node(1)).norm()) < 1e-12);
}

TEST_CASE("valve_landmark_curves: a wholly attached boundary is a closed annulus", "[slicer_markups]") {
  TriMesh m = test::grid_mesh(2.0);
  for (int n : {0, 1, 2, 3, 5, 6, 7, 8}) m.boundary[n] = BoundaryType::attached;
  const auto curves = valve_landmark_curves(m, flatten(m.points));
  REQUIRE(curves.size() == 1);
  CHECK(curves[0].name == "annulus");
  CHECK(curves[0].closed);
  CHECK(curves[0].points.rows() == 8);
}

TEST_CASE("valve_landmark_curves: the coaptation line does not wrap from one end of an edge to the other", "[slicer_markups]") {
  // Free edge 0-1-2 with its two ends coapting and the middle not: two one-node stretches, no line.
  TriMesh m = test::grid_mesh(2.0);
  for (int n : {0, 2, 3, 5, 6, 7, 8}) m.boundary[n] = BoundaryType::attached;
  m.boundary[1] = BoundaryType::free_edge;
  const std::vector<int> coapting = {1, 0, 1, 0, 0, 0, 0, 0, 0};
  const auto curves = valve_landmark_curves(m, flatten(m.points), &coapting);
  for (const auto& c : curves) CHECK((c.name.rfind("coaptation", 0) != 0 || c.points.rows() < 2));
}
