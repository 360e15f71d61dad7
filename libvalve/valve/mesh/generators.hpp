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

}  // namespace valve
