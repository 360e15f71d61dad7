#include <catch2/catch.hpp>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "../support/test_meshes.hpp"
#include "valve/io/mesh_io.hpp"
#include "valve/scene/closure_files.hpp"

using namespace valve;
namespace fs = std::filesystem;

namespace {
fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("valve_closure_files_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}
}  // namespace

TEST_CASE("read_leaflet_mesh refuses a mesh without fiber directions, naming file and array", "[scene][io]") {
  const fs::path dir = fresh_dir("fibers");
  TriMesh mesh = test::grid_mesh();
  write_mesh(dir / "with.vtp", mesh);
  CHECK(read_leaflet_mesh(dir / "with.vtp").num_triangles() == 8);
  mesh.fiber.resize(0, 3);  // the writer then leaves the array out
  write_mesh(dir / "without.vtp", mesh);
  CHECK_THROWS_WITH(read_leaflet_mesh(dir / "without.vtp"),
                    Catch::Contains("without.vtp") && Catch::Contains("FiberDirection") && Catch::Contains("found none"));
}

TEST_CASE("the time series keeps every n-th step and the index lists exactly those", "[scene][io]") {
  const fs::path dir = fresh_dir("series");
  const TriMesh mesh = test::grid_mesh();
  ClosureTimeSeries series(dir, mesh, true, 3);
  for (int k = 1; k <= 7; ++k) series.step(mesh.points, 0.5 * k);
  series.finish();
  CHECK(series.steps() == 7);
  CHECK(fs::exists(dir / "series/step_3.vtp"));
  CHECK(fs::exists(dir / "series/step_6.vtp"));
  CHECK_FALSE(fs::exists(dir / "series/step_7.vtp"));
  std::ifstream pvd(dir / "closed.sim.pvd");
  std::stringstream text;
  text << pvd.rdbuf();
  CHECK(text.str().find("series/step_3.vtp") != std::string::npos);
  CHECK(text.str().find("timestep=\"3\"") != std::string::npos);  // step 6 at t = 3 ms
  CHECK(text.str().find("step_1.vtp") == std::string::npos);

  ClosureTimeSeries off(dir / "off", mesh, false, 1);
  off.step(mesh.points, 1.0);
  off.finish();
  CHECK_FALSE(fs::exists(dir / "off"));
}

TEST_CASE("remove_closure_files clears an earlier run's outputs but not other files", "[scene][io]") {
  const fs::path dir = fresh_dir("remove");
  fs::create_directories(dir / "series");
  for (const char* name : {"closed.sim.vtp", "closed.sim.stl", "closed.chordae.vtp", "coaptation_columns.csv",
                           "closed.landmarks.mrk.json", "closed.sim.pvd", "series/step_10.vtp", "simulate.summary.json",
                           "series/notes.txt"})
    std::ofstream(dir / name) << "x";
  remove_closure_files(dir);
  std::vector<std::string> left;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) left.push_back(fs::relative(e.path(), dir).string());
  std::sort(left.begin(), left.end());
  CHECK(left == std::vector<std::string>{"series/notes.txt", "simulate.summary.json"});
}
