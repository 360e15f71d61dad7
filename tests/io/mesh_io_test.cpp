// Reading the coordinate-system tag 3D Slicer writes into meshes. The files are written here as
// plain text in each format's own syntax, so the expected coordinates come from the format
// (RAS x, y negated into LPS), not from the reader under test.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "valve/core/error.hpp"
#include "valve/io/mesh_io.hpp"

namespace fs = std::filesystem;
using namespace valve;

namespace {

fs::path write_text(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / "valve_mesh_io_test";
  fs::create_directories(dir);
  std::ofstream(dir / name) << text;
  return dir / name;
}

// One triangle with distinct, non-zero coordinates in every axis.
const double kP[3][3] = {{1, 2, 3}, {4, -5, 6}, {-7, 8, 9}};

std::string legacy_vtk(const std::string& header) {
  return "# vtk DataFile Version 4.2\n" + header + "\nASCII\nDATASET POLYDATA\nPOINTS 3 double\n"
         "1 2 3\n4 -5 6\n-7 8 9\nPOLYGONS 1 4\n3 0 1 2\n";
}

// VTK XML stores a string array in ASCII as character codes, each string ending in 0.
std::string xml_vtp(const std::string& space) {
  std::string codes;
  for (char c : space) codes += std::to_string(int(c)) + " ";
  const std::string field = space.empty() ? "" :
      "<FieldData><Array type=\"String\" Name=\"SPACE\" NumberOfTuples=\"1\" format=\"ascii\">" + codes + "0</Array></FieldData>";
  return "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n<PolyData>" + field +
         "<Piece NumberOfPoints=\"3\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"1\">"
         "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">1 2 3 4 -5 6 -7 8 9</DataArray></Points>"
         "<Polys><DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">0 1 2</DataArray>"
         "<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">3</DataArray></Polys></Piece></PolyData></VTKFile>\n";
}

// `mirrored`: the file is in RAS, so x and y come back negated.
void check_points(const TriMesh& m, bool mirrored) {
  REQUIRE(m.num_nodes() == 3);
  const double s = mirrored ? -1 : 1;
  for (int i = 0; i < 3; ++i) {
    CHECK(m.points(i, 0) == Approx(s * kP[i][0]));
    CHECK(m.points(i, 1) == Approx(s * kP[i][1]));
    CHECK(m.points(i, 2) == Approx(kP[i][2]));
  }
}

}  // namespace

TEST_CASE("read_mesh honours Slicer's SPACE tag in every format it reads", "[mesh_io]") {
  SECTION("legacy .vtk header") {
    check_points(read_mesh(write_text("ras.vtk", legacy_vtk("3D Slicer output. SPACE=RAS"))), true);
    check_points(read_mesh(write_text("lps.vtk", legacy_vtk("3D Slicer output. SPACE=LPS"))), false);
    check_points(read_mesh(write_text("untagged.vtk", legacy_vtk("a mesh"))), false);
  }
  SECTION(".vtp field data") {
    check_points(read_mesh(write_text("ras.vtp", xml_vtp("RAS"))), true);
    check_points(read_mesh(write_text("lps.vtp", xml_vtp("LPS"))), false);
    check_points(read_mesh(write_text("untagged.vtp", xml_vtp(""))), false);
  }
  SECTION("STL header, PLY comment, OBJ comment") {
    check_points(read_mesh(write_text("ras.stl",
        "solid 3D Slicer output. SPACE=RAS\nfacet normal 0 0 1\nouter loop\nvertex 1 2 3\nvertex 4 -5 6\n"
        "vertex -7 8 9\nendloop\nendfacet\nendsolid\n")), true);
    check_points(read_mesh(write_text("ras.ply",
        "ply\nformat ascii 1.0\ncomment SPACE=RAS\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
        "1 2 3\n4 -5 6\n-7 8 9\n3 0 1 2\n")), true);
    check_points(read_mesh(write_text("ras.obj", "# 3D Slicer output. SPACE=RAS\nv 1 2 3\nv 4 -5 6\nv -7 8 9\nf 1 2 3\n")), true);
  }
  SECTION("the line reader too") {
    const auto segments = read_line_segments(write_text("ras_lines.vtk",
        "# vtk DataFile Version 4.2\n3D Slicer output. SPACE=RAS\nASCII\nDATASET POLYDATA\nPOINTS 2 double\n"
        "1 2 3\n4 -5 6\nLINES 1 3\n2 0 1\n"));
    REQUIRE(segments.size() == 1);
    CHECK(segments[0].first.x() == Approx(-1));
    CHECK(segments[0].first.y() == Approx(-2));
    CHECK(segments[0].second.y() == Approx(5));
  }
}

TEST_CASE("read_mesh refuses a SPACE it does not know, naming the file and the tag", "[mesh_io]") {
  const auto header = write_text("ijk.vtk", legacy_vtk("SPACE=IJK"));
  CHECK_THROWS_WITH(read_mesh(header), Catch::Contains("ijk.vtk") && Catch::Contains("SPACE: expected RAS or LPS, found \"IJK\""));
  const auto field = write_text("ijk.vtp", xml_vtp("right-anterior-superior"));
  CHECK_THROWS_AS(read_mesh(field), InputError);
  CHECK_THROWS_WITH(read_mesh(field), Catch::Contains("found \"right-anterior-superior\""));
}

TEST_CASE("a mesh written by write_mesh reads back unmirrored (its SPACE=LPS)", "[mesh_io]") {
  TriMesh m;
  m.points.resize(3, 3);
  for (int i = 0; i < 3; ++i) m.points.row(i) << kP[i][0], kP[i][1], kP[i][2];
  m.triangles = {Tri(0, 1, 2)};
  m.fill_defaults();
  const fs::path p = fs::temp_directory_path() / "valve_mesh_io_test" / "ours.vtp";
  write_mesh(p, m);
  check_points(read_mesh(p), false);
}
