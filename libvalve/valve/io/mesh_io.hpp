#pragma once
// Reading and writing triangle meshes through VTK. Reads .vtp (default), .vtk, .vtu,
// .stl, .ply and .obj; writes .vtp (or legacy .vtk) with named point and cell arrays:
//   FiberDirection (cell, 3), NodeRole (point), BoundaryType (point), Leaflet (cell),
// plus any extra arrays (Displacement, Stretch, GreenStrain, ...), and the field SPACE=LPS.
// It also writes binary .stl and .ply and ASCII .obj for printing and CAD: their readers
// take geometry only (.ply and .obj carry no named arrays that other tools read), so those
// copies hold the points (in LPS mm) and triangles, and a stage's .vtp stays its output.
// A mesh whose starting positions differ from its rest shape (a graft sewn in under
// compression) carries them as the point array InitialDisplacement (initial − rest).
#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "valve/mesh/named_array.hpp"
#include "valve/mesh/tri_mesh.hpp"

namespace valve {

/// Reads a triangle mesh. Throws InputError (file, what was expected, what was found) for
/// unreadable files, unknown extensions, non-triangle cells and meshes without cells.
/// A mesh 3D Slicer tagged SPACE=RAS (field data, or its header or comment) is converted to
/// LPS; untagged is LPS; any other SPACE value is an InputError.
/// Arrays the file lacks are filled with defaults (TriMesh::fill_defaults); `extra`, when
/// given, receives every named point and cell array as it is in the file.
TriMesh read_mesh(const std::filesystem::path& path, std::vector<NamedArray>* extra = nullptr);

/// The extensions write_mesh takes.
inline const std::vector<std::string> kMeshWriteExtensions = {".vtp", ".vtk", ".stl", ".ply", ".obj"};
/// The formats a stage's --mesh-copies may name (kMeshWriteExtensions without the dot).
inline const std::vector<std::string> kMeshCopyFormats = {"vtk", "stl", "ply", "obj"};

/// Writes `mesh` with point coordinates `positions` (the rest positions if null) and the
/// extra arrays, atomically, in the format of the extension (kMeshWriteExtensions).
void write_mesh(const std::filesystem::path& path, const TriMesh& mesh, const MatX3* positions = nullptr,
                const std::vector<NamedArray>& extra = {});

/// The formats of a stage's --mesh-copies value ("stl,obj"; repeats dropped; none when
/// unset). Throws InputError naming the flag for a format not in kMeshCopyFormats.
std::vector<std::string> parse_mesh_copies(const std::optional<std::string>& value);

/// write_mesh to `path` with its stem and each extension of `formats` (kMeshCopyFormats, a
/// stage's --mesh-copies stl,obj): copies of a stage's result mesh for other tools.
void write_mesh_copies(const std::filesystem::path& path, const std::vector<std::string>& formats, const TriMesh& mesh,
                       const MatX3* positions = nullptr, const std::vector<NamedArray>& extra = {});

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
