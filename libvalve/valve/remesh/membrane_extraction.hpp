#pragma once
// From the closed surface of a thick leaflet sheet (both faces and the rim, as triangulated
// from a scan) to the leaflet membrane the mechanics needs (seed 5.2.2 keeps the atrial
// surface of the open valve):
//   1. A face belongs to the atrial side when its outward normal points toward an atrial
//      viewpoint V = c + h D a (c the centroid, D the bounding-box diagonal, a the atrial
//      direction): n · (V − x) > 0. For an open funnel-shaped valve and a closed domed one the
//      atrial face is the one facing up the valve axis; the ventricular face looks away.
//   2. The labels are smoothed by majority votes over edge neighbours, so that the rim splits
//      cleanly and noise does not leave islands, then closed morphologically (grow n face
//      rings, shrink n) so that slits and notches at the rim do not reach into the membrane.
//   3. The selected faces are split into connected pieces; pieces under a fraction of the
//      largest one's area are dropped.
// The atrial direction is given, or estimated: the valve is wider than it is deep, so the
// axis is the direction of least spread of the points (PCA), signed so that the wider part
// (the annulus) is atrial.
#include <optional>

#include "valve/mesh/tri_mesh.hpp"

namespace valve {

struct MembraneOptions {
  std::optional<Vec3> atrial_direction;
  double viewpoint_height = 2;         // h in V = c + h D a (D the bounding-box diagonal)
  int smoothing_passes = 10;
  int closing_rings = 2;               // face rings of the morphological closing of the selection
  double min_piece_fraction = 0.05;    // of the largest piece's area
};

struct MembraneSummary {
  Vec3 atrial_direction = Vec3::UnitZ();
  bool direction_estimated = false;
  int faces_in = 0, faces_kept = 0;
  int pieces_kept = 0, pieces_dropped = 0;
  double area_mm2 = 0;
};

/// Throws InputError if nothing faces the atrium.
TriMesh extract_atrial_membrane(const TriMesh& surface, const MembraneOptions& options, MembraneSummary* summary);

/// PCA axis of least spread, signed so that points far from the axis lie on its positive side.
Vec3 estimate_atrial_direction(const MatX3& points);

/// The membrane of an input that already is one (a mid-surface, e.g. a finite element
/// model): the surface itself, every face kept. The summary's atrial direction is the given
/// one, normalized, or estimated from the points (estimate_atrial_direction) when none is.
MembraneSummary describe_given_membrane(const TriMesh& surface, const std::optional<Vec3>& atrial_direction);


/// Marks boundary loops: the loop lying farthest along `atrial_direction` (mean height) is the
/// annulus (NodeRole fixed, BoundaryType attached); every other loop is free edge. Sets fibers
/// circumferential about the axis through the centroid along `atrial_direction`. Returns the
/// number of loops.
int mark_annulus_and_free_edge(TriMesh& mesh, const Vec3& atrial_direction);

/// The annulus as a landmark: the edges of `reference` whose two nodes are both attached
/// (BoundaryType), e.g. the annulus ring of an atlas or of the model a scan was made from.
/// Throws InputError (naming `file`) when the reference marks no such edge.
std::vector<std::pair<Vec3, Vec3>> annulus_segments(const TriMesh& reference, const std::string& file);

/// Like mark_annulus_and_free_edge, but a boundary node is annulus when it lies within
/// `tolerance` (mm) of the landmark segments, and free edge otherwise, whichever loop it is
/// on. Why: where the membrane of an open scan loses part of a leaflet, its outer boundary
/// loop runs down into the leaflets (voxelized open Texas TriValve: a 122 mm outer loop
/// around a 98 mm annulus), and fixing that whole loop holds leaflet tissue in place.
/// Throws InputError naming `landmark_file` when no boundary node is that close. Returns the
/// number of loops.
int mark_annulus_near(TriMesh& mesh, const std::vector<std::pair<Vec3, Vec3>>& annulus, double tolerance,
                      const Vec3& atrial_direction, const std::string& landmark_file = "annulus landmark");

}  // namespace valve
