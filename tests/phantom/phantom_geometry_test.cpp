// The geometry a phantom image is made of, from each of its sources, its grid and the
// summary's file names, checked against the inputs they are built from.
#include <catch2/catch.hpp>

#include "valve/core/error.hpp"
#include "valve/phantom/phantom_geometry.hpp"

using namespace valve;

TEST_CASE("mitral phantom geometry: chordae as tubes and network, or none", "[phantom]") {
  MitralPhantomOptions o;
  o.variation = 0;
  o.thickness = 0.8;
  const PhantomGeometry with = mitral_phantom_geometry(o, true);
  REQUIRE(with.chordae);
  CHECK(with.chord_segments.size() == with.chordae->segments.size());
  CHECK(with.papillary.size() == 2);
  CHECK(with.thickness == 0.8);
  CHECK(with.description["chordae"]["segments"] == with.chordae->segments.size());
  CHECK(with.description["valve"]["commissural_diameter_mm"] == 30.0);
  // Each tube runs between the network's points.
  const auto& s0 = with.chordae->segments[0];
  CHECK(with.chord_segments[0].first == with.chordae->points[s0.from].position);

  const PhantomGeometry without = mitral_phantom_geometry(o, false);
  CHECK_FALSE(without.chordae);
  CHECK(without.chord_segments.empty());
  CHECK(without.papillary.empty());
  CHECK(without.description["chordae"]["segments"] == 0);
  CHECK(without.description["chordae"]["insertions"] == 0);
  CHECK(without.leaflets.num_triangles() == with.leaflets.num_triangles());
}

TEST_CASE("model phantom geometry: shells, trusses and a frame of the deck's size", "[phantom]") {
  const AbaqusModel model = read_abaqus_inp(VALVE_TEST_DATA_DIR "/two_quads.inp");
  ModelPhantomOptions o{"two_quads.inp"};
  const PhantomGeometry g = model_phantom_geometry(model, o);
  CHECK(g.leaflets.num_triangles() == 4);  // two quads
  CHECK(g.thickness == 0.65);
  REQUIRE(g.chord_segments.size() == 1);  // node 10 at z = -5 to node 1 at the origin
  CHECK(g.chord_segments[0].first == Vec3(0, 0, -5));
  CHECK(g.chord_segments[0].second == Vec3(0, 0, 0));
  REQUIRE(g.chordae);
  CHECK(g.description["chordae"]["papillary_tips"] == 1);  // node 10 is held in x, y and z
  CHECK(g.description["annulus_nodes"] == 3);
  CHECK(g.description["free_edge_nodes"] == 3);
  CHECK(g.description["frame"] == "(the .inp coordinates)");
  CHECK(g.has_leaflet_materials());

  // A frame moves every node: the strip raised by 2 mm.
  MatX3 raised = model.points;
  raised.col(2).array() += 2;
  o.frame_file = "frame.vtu";
  o.with_chordae = false;
  const PhantomGeometry moved = model_phantom_geometry(model, o, raised);
  CHECK(moved.leaflets.points.col(2).minCoeff() == 2);
  CHECK(moved.chord_segments.empty());
  CHECK_FALSE(moved.chordae);
  CHECK(moved.description["frame"] == "frame.vtu");
  CHECK_THROWS_WITH(model_phantom_geometry(model, o, MatX3(raised.topRows(3))),
                    "frame.vtu: expected 7 points (one per node of two_quads.inp), found 3");
}

TEST_CASE("phantom grid: the box of every part widened by margin and thickness", "[phantom]") {
  PhantomGeometry g;
  g.leaflets.points.resize(3, 3);
  g.leaflets.points << 0, 0, 0, 4, 0, 0, 0, 2, 1;
  g.thickness = 0.5;
  g.chord_segments = {{Vec3(1, 1, -3), Vec3(1, 1, 0)}};
  g.papillary.push_back({Vec3::Zero(), Vec3(1, 1, -4), Vec3(0.5, 0.5, 1)});  // reaches z = -5
  const ImageGeometry grid = phantom_grid(g, 0.5, 1);
  // lo = (0, 0, -5) - 1.5, hi = (4, 2, 1) + 1.5; 0.5 mm voxels, both ends included.
  CHECK(grid.origin.isApprox(Vec3(-1.5, -1.5, -6.5)));
  CHECK(grid.size == std::array<int, 3>{15, 11, 19});
  CHECK(grid.spacing == Vec3::Constant(0.5));

  const nlohmann::json m = phantom_metrics(g, grid, "open", "nii");
  CHECK(m["image"] == "open.nii.gz");
  CHECK(m["truth"] == "open.truth.vtp");
  CHECK(m["spacing_mm"] == 0.5);
  CHECK(m["size"] == nlohmann::json{15, 11, 19});
  CHECK_FALSE(m.contains("chordae_file"));
  CHECK_FALSE(m.contains("leaflet_materials_file"));
}

TEST_CASE("phantom image file: one name per format", "[phantom]") {
  CHECK(phantom_image_file("open", "nrrd") == "open.nrrd");
  CHECK(phantom_image_file("open", "mha") == "open.mha");
  CHECK(phantom_image_file("open", "nii") == "open.nii.gz");
  CHECK(phantom_image_file("open", "dicom") == "open.dicom");
}

TEST_CASE("phantom voxels: tissue inside the sheet, background away from it", "[phantom]") {
  PhantomGeometry g;
  g.leaflets.points.resize(4, 3);
  g.leaflets.points << 0, 0, 0, 4, 0, 0, 4, 4, 0, 0, 4, 0;
  g.leaflets.triangles = {Tri(0, 1, 2), Tri(0, 2, 3)};
  g.thickness = 1;
  const ImageGeometry grid = phantom_grid(g, 0.25, 1);
  Progress quiet("test", true);
  const Volume v = voxelize_phantom(g, grid, -10, 90, quiet);
  const auto at = [&](const Vec3& p) {
    const Vec3 i = grid.continuous_index(p);
    return v.values[grid.linear_index(int(std::lround(i.x())), int(std::lround(i.y())), int(std::lround(i.z())))];
  };
  CHECK(at(Vec3(2, 2, 0)) == Approx(90));
  CHECK(at(Vec3(2, 2, 1.5)) == Approx(-10));
}
