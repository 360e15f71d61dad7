#pragma once
// A parametric mitral valve in its open state, the ground truth of the imaging tests.
//
// Frame: the valve axis is +z, pointing to the atrium; the annulus centre is the origin;
// +y points to the anterior (aortic) side, x runs commissure to commissure.
//   Annulus: a D shape, x = a cos θ, y = b sin θ (0.9 − 0.1 sin θ) (flatter on the anterior
//   side), saddle z = (h/2)(−cos 2θ): high anteriorly and posteriorly, low at the commissures.
//   Leaflets: one continuous skirt hanging from the annulus, tilted by α toward the axis,
//   point(θ, s) = A(θ) + s L(θ) d(θ) + b sin(πs) e(θ), s ∈ [0, 1] from annulus to free edge,
//   with d = −sin α r̂ − cos α ẑ, e = cos α r̂ − sin α ẑ (the ventricular side) and a length
//   L(θ) that falls to the commissure length at the two commissures, peaks at the anterior
//   length mid-anterior, and has two clefts splitting the posterior leaflet into the
//   scallops P1, P2, P3.
//   Papillary muscles: ellipsoids below the two commissures, tips on top.
//   Chordae: from each tip, fans of primary chords (tip → branch point → 3 free-edge
//   insertions), secondary chords to the belly of both leaflets, and two strut chords to the
//   anterior leaflet; each muscle serves its own half (x > 0 or x < 0) of the valve.
// Triangle normals point to the atrial side (toward the axis and up).
#include <cstdint>

#include "valve/chordae/chordae_network.hpp"
#include "valve/mesh/tri_mesh.hpp"

namespace valve {

struct MitralPhantomOptions {
  double commissural_diameter = 30.0;     // mm, x extent of the annulus
  double septal_lateral_diameter = 25.0;  // mm, y extent
  double saddle_height = 4.0;             // mm, annulus height high-to-low
  double anterior_length = 22.0;          // mm, annulus to free edge, mid-anterior
  double posterior_length = 13.0;         // mm, mid-scallop
  double commissure_length = 7.0;         // mm
  double cleft_depth = 0.55;              // fraction of the posterior length lost at a cleft
  double opening_angle_deg = 25.0;        // tilt α of the leaflets toward the axis
  double belly_bulge = 1.0;               // mm, toward the ventricle
  double anterior_span_deg = 130.0;       // angular extent of the anterior leaflet on the annulus
  double thickness = 1.0;                 // mm, leaflet thickness (for voxelization)
  double chord_diameter = 0.5;            // mm
  double papillary_radius = 3.0;          // mm, ellipsoid semi-axes (r, r, 1.7 r)
  double papillary_depth = 26.0;          // mm, papillary tips below the annulus plane
  double edge_length = 0.4;               // mm, ground-truth mesh resolution
  double variation = 0.08;                // relative random variation of every size (0: nominal)
  std::uint64_t seed = 1;
};

struct PapillaryMuscle {
  Vec3 tip = Vec3::Zero();
  Vec3 centre = Vec3::Zero();
  Vec3 semi_axes = Vec3::Ones();  // along x, y, z
};

struct MitralPhantom {
  MitralPhantomOptions options;     // after the random variation
  TriMesh leaflets;                 // mid-surface, BoundaryType attached on the annulus, free_edge on the free edge; Leaflet 0 anterior, 1 posterior
  ChordaeNetwork chordae;           // insertions carry leaflets' node indices
  PapillaryMuscle papillary[2];     // 0 anterolateral (x > 0), 1 posteromedial (x < 0)
  Vec3 atrial_direction = Vec3::UnitZ();
};

MitralPhantom make_mitral_phantom(const MitralPhantomOptions& options);

}  // namespace valve
