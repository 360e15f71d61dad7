#pragma once
// Cut-plane sections of leaflet meshes (seed Fig. 5.9: the closed valve before and after a
// chord is shortened, compared plane by plane). The planes are perpendicular to the
// commissure-to-commissure axis, taken as the longest principal axis of the annulus ring,
// at `count` evenly spaced stations strictly inside the ring's extent along it; each cut is
// drawn in the plane's own 2-D frame: u along the ring's second principal axis (anterior to
// posterior) and v along the ring's normal (the third axis, pointing to the side given).
//
// Written here rather than with vtkCutter: a plane meets a triangle in at most one segment,
// which is all the plots need (no polyline stitching), and the analysis then needs no VTK.
#include <nlohmann/json.hpp>
#include <vector>

#include "valve/mesh/tri_mesh.hpp"

namespace valve {

struct SectionFrame {
  Vec3 origin = Vec3::Zero();          // ring centroid
  Vec3 axis = Vec3::UnitX();           // plane normal: commissure to commissure
  Vec3 u = Vec3::UnitY(), v = Vec3::UnitZ();
  std::vector<double> offsets;         // station of each plane along `axis` from the origin (mm)
};

/// Frame and `count` stations from the annulus ring points (rows). `up` orients v (e.g. the
/// atrial direction); a zero vector leaves the principal axis's sign.
SectionFrame section_frame(const MatX3& ring, int count, const Vec3& up = Vec3::Zero());

struct SectionSegment {
  int plane = 0;                 // index into SectionFrame::offsets
  double u0, v0, u1, v1;         // mm in the plane's frame
};

/// The segments where each plane cuts the mesh at positions `points` (rows, one per node).
std::vector<SectionSegment> cut_sections(const TriMesh& mesh, const MatX3& points, const SectionFrame& frame);

nlohmann::json to_json(const SectionFrame& frame);

}  // namespace valve
