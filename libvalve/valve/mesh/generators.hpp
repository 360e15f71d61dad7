#pragma once
// Analytic test meshes of the seed (3.2.2.1, Fig. 3.1): a square patch for biaxial tests,
// a semicircular aortic leaflet fixed along its semi-circumference to the inside wall of
// a cylinder, and three such leaflets wrapped into that cylinder.
#include <cstdint>

#include "valve/mesh/planar_mesher.hpp"
#include "valve/mesh/tri_mesh.hpp"

namespace valve {

struct SquarePatchOptions {
  double side = 15.0;             // mm
  double fiber_angle_deg = 0.0;   // fiber direction measured from +x
  PlanarMeshOptions mesh{229, 1};
};
/// Square in the z = 0 plane centred at the origin, normals +z, all nodes free; boundary
/// nodes are marked free_edge.
TriMesh generate_square_patch(const SquarePatchOptions& opt);

struct DiskOptions {
  double diameter = 20.0;         // mm
  double fiber_angle_deg = 0.0;   // fiber direction measured from +x
  PlanarMeshOptions mesh{300, 1};
};
/// Disk in the z = 0 plane centred at the origin, normals +z; its rim nodes are fixed
/// (BoundaryType attached): the clamped plate of a pressure test and of the CalculiX cross-check.
TriMesh generate_clamped_disk(const DiskOptions& opt);

struct LeafletOptions {
  double diameter = 20.0;                // mm, semicircle diameter = unstressed free-edge length
  double cylinder_circumference = 60.0;  // mm
  double fiber_angle_deg = 0.0;          // fiber angle to the free edge
  PlanarMeshOptions mesh{221, 1};
};
/// One semicircular leaflet on the cylinder x² + y² = R², R = circumference / 2π, centred
/// on the +x axis (unrolled: u = R φ along the free edge, v = z), free edge at z = 0, belly down to z = -diameter/2. Nodes on the
/// semi-circumference are fixed (BoundaryType attached), free-edge nodes free. Triangle
/// normals point toward the cylinder axis, the side the aortic pressure pushes toward.
TriMesh generate_aortic_leaflet(const LeafletOptions& opt);

/// Three identical semicircular leaflets joined at the commissures (shared corner nodes)
/// and wrapped into a cylinder of circumference 3 × diameter (cylinder_circumference is
/// ignored). Leaflet k is centred on the ray at angle 2πk/3 in the xy plane.
TriMesh generate_three_leaflet_valve(const LeafletOptions& opt);

/// The aortic valve of seed 4.2.1 (Fig. 4.1-4.2): each leaflet, flat, is bounded below by
/// the attachment curve y = d sin²(x/d) / tan γ (x from the midline, |x| <= w/2, w = 1.047 d,
/// i.e. a third of the root circumference: the unrolled intersection of the root cylinder
/// with a plane tilted by γ), on the sides by the commissures (height h_c) and on top by the
/// straight free edge. Three leaflets meet at the commissures, wrapped into the cylinder of
/// diameter d, free edges at z = 0 for native leaflets, normals toward the axis. They share no
/// nodes: w = 1.047 d falls short of a third of the circumference (π d / 3), so neighbouring
/// sides lie 2 e-4 d apart (0.004 mm at 20 mm), and the barrier contact acts on such pairs
/// within half that gap (narrow pairs, contact_base.hpp).
///
/// Grafts: leaflet k's flat shape may be scaled by width_scale[k] and height_scale[k]. Its
/// nadir stays on the root's; a taller graft reaches higher up the commissures (seed 4.4).
/// A wider graft has more free edge than its third of the root: its rest shape is wrapped
/// on a cylinder of radius width_scale · d/2 (an isometry) and it starts at the root's radius,
/// compressed circumferentially (TriMesh::initial) until the pressure takes up the slack.
/// A graft is sewn beside its neighbours, not onto their commissure lines: its start angles
/// are drawn in so that its sides lie graft_commissure_gap along the root wall from theirs,
/// which gathers its attachment by 2 gap / w (2.9 % at the default). Sewn onto the same line,
/// the two leaflets' triangles start within the contact's reach: the penalty contact leaves
/// them out, and they hinge through each other at the wall as they close (the graft study with
/// BDF2: 522 intersecting pairs in 45 of 180 closures, none with the gap); the barrier keeps
/// them as narrow pairs (none at equilibrium either way). The default, 0.3 mm, is the smallest
/// round value above the contact models' default reach (0.25 mm), so that no pair of the two
/// leaflets starts within it; the sizing study's dependence on it: docs/results/aortic-valve.md.
///
/// Fibers (Fig. 4.6): parallel to the free edge, or at |fiber_angle_deg| to it in a pattern
/// symmetric about the midline: a positive angle runs down toward the midline like a hammock,
/// a negative one (the default, -25°) rises toward it. The normal valve's choice and its
/// evidence: configs/aortic_valve_normal.json.
struct AorticValveOptions {
  double diameter = 20.0;           // mm, root diameter the leaflets are unstressed at
  double gamma_deg = 22.0;
  double width_ratio = 1.047;       // leaflet width / diameter
  double commissure_height = 5.0;   // mm
  double fiber_angle_deg = -25.0;   // 0 = parallel to the free edge
  double width_scale[3] = {1, 1, 1};
  double height_scale[3] = {1, 1, 1};
  double graft_commissure_gap = 0.3;  // mm, along the root wall (start positions) on each side of a graft
  PlanarMeshOptions mesh{220, 1};   // per leaflet
};
TriMesh generate_aortic_valve(const AorticValveOptions& opt);

}  // namespace valve
