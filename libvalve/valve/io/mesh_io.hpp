#pragma once
// Reading and writing triangle meshes through VTK. Reads .vtp (default), .vtk, .vtu,
// .stl, .ply and .obj; writes .vtp with named point and cell arrays:
//   FiberDirection (cell, 3), NodeRole (point), BoundaryType (point), Leaflet (cell),
// plus any extra arrays (Displacement, Stretch, GreenStrain, ...), and the field SPACE=LPS.
// A mesh whose starting positions differ from its rest shape (a graft sewn in under
// compression) carries them as the point array InitialDisplacement (initial − rest).
#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

#include "valve/mesh/tri_mesh.hpp"

namespace valve {

struct NamedArray {
  std::string name;
  Eigen::MatrixXd values;  // one row per point (or cell), one column per component
  bool per_cell = false;
};

/// Reads a triangle mesh. Throws InputError (file, what was expected, what was found) for
/// unreadable files, unknown extensions, non-triangle cells and meshes without cells.
/// A mesh 3D Slicer tagged SPACE=RAS (field data, or its header or comment) is converted to
/// LPS; untagged is LPS; any other SPACE value is an InputError.
/// Arrays the file lacks are filled with defaults (TriMesh::fill_defaults); `extra`, when
/// given, receives every named point and cell array as it is in the file.
TriMesh read_mesh(const std::filesystem::path& path, std::vector<NamedArray>* extra = nullptr);

/// Writes `mesh` with point coordinates `positions` (the rest positions if null) and the
/// extra arrays, atomically. The extension must be .vtp (or .vtk for legacy readers).
void write_mesh(const std::filesystem::path& path, const TriMesh& mesh, const MatX3* positions = nullptr,
                const std::vector<NamedArray>& extra = {});

/// Writes a line set (.vtp with line cells, for ParaView), e.g. chordae: `points` with
/// per-point arrays, `lines` node pairs with per-line arrays (NamedArray::per_cell).
void write_lines(const std::filesystem::path& path, const MatX3& points, const std::vector<std::pair<int, int>>& lines,
                 const std::vector<NamedArray>& arrays = {});

/// The segments of every polyline of a .vtp line set (e.g. closed.chordae.vtp), as end-point
/// pairs. Throws InputError naming the file when it has no line cells.
std::vector<std::pair<Vec3, Vec3>> read_line_segments(const std::filesystem::path& path);

/// The point coordinates of any VTK XML data set (.vtu, .vtp), in file order: a frame of a
/// model whose points follow its node numbering (Texas TriValve: point i = node i + 1).
MatX3 read_point_positions(const std::filesystem::path& path);

/// Writes a ParaView .pvd collection that lists `files` (relative names) at `times`.
void write_pvd(const std::filesystem::path& path, const std::vector<std::string>& files,
               const std::vector<double>& times);

}  // namespace valve
