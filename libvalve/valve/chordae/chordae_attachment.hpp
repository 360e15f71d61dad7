#pragma once
// Puts a chordae network on a leaflet mesh for simulation (seed 5.2.2): insertions become
// the mesh nodes they are snapped to, papillary tips and branch points become extra nodes
// appended after the mesh nodes (tips fixed, branch points free, with the chords' mass),
// and every segment becomes a tension-only rod.
//
// Condensed chains (ChordMaterial::condense_chains): a run of segments through branch points
// that join exactly two segments of one law and section becomes one rod from the run's first
// to its last point, its rest length the sum of theirs. Nothing loads a chord between its
// ends, so at equilibrium a taut run is straight and evenly stretched (the law's energy is
// convex in the stretch, so by Jensen's inequality an even stretch stores the least energy
// for the run's length) and a slack one carries nothing: the condensed rod stores the
// least energy the run can have, and the leaflets feel the same chordae at every
// equilibrium. The points inside a run are then no unknowns (held, massless; each end keeps
// the mass it has with every point a node) and are drawn on the rod's line by rest length.
// The Texas TriValve deck's network has 2,330 such points among 2,424 branch points.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "valve/chordae/chordae_network.hpp"
#include "valve/mechanics/chordae_rods.hpp"
#include "valve/mesh/tri_mesh.hpp"

namespace valve {

/// Snaps every insertion to the nearest mesh node and moves it there. An insertion farther
/// than `tolerance` (mm) from every node is an InputError naming the chord (its point index
/// and name) and the distance found.
void snap_insertions(ChordaeNetwork& network, const MatX3& mesh_points, double tolerance, const std::string& file);

/// The laws the rods take: a segment whose material names one of `named_laws` takes that law
/// and its own section (area_mm2, else the network's diameter); every other segment takes
/// `default_law` (seed Table 5.1: linear, E = 40 MPa). `diameter` > 0 sets every section.
struct ChordMaterial {
  std::shared_ptr<const RodLaw> default_law = std::make_shared<LinearRodLaw>(40.0);
  std::map<std::string, std::shared_ptr<const RodLaw>> named_laws;
  double diameter = 0;       // mm; 0 = the segment's area_mm2, else the network's diameter
  double density = 1.06e-3;  // g/mm³, as the leaflets
  bool condense_chains = false;
};

struct ChordaeAttachment {
  int mesh_nodes = 0;             // nodes 0..mesh_nodes-1 are the leaflets'
  std::vector<int> point_node;    // system node of every network point
  MatX3 extra_points;             // papillary tips and branch points, in network order
  std::vector<NodeRole> extra_roles;
  std::vector<double> extra_mass;  // g: half of each adjoining chord's mass
  std::vector<Rod> rods;           // one per segment, in network order (condensed: one per run)
  std::vector<int> segment_rod;    // the rod that carries each network segment
  /// Points inside a condensed run: the run's rod and the point's share of its rest length
  /// from the rod's end a; -1 and 0 for every other point.
  std::vector<int> run_rod;
  std::vector<double> run_fraction;

  /// Every network point's position in state x (a point inside a run on its rod's line).
  MatX3 point_positions(const VecX& x) const;
  /// Every network segment's tension from its rod's (rod_tensions in rods' order).
  std::vector<double> segment_tensions(const std::vector<double>& rod_tensions) const;
};

/// Builds the rods (law and section as ChordMaterial says, rest length from
/// ChordaeNetwork::rest_length) for a network whose insertions are snapped to a mesh of
/// `mesh_nodes` nodes.
ChordaeAttachment attach_chordae(const ChordaeNetwork& network, int mesh_nodes, const ChordMaterial& material);

/// The mesh with the attachment's extra nodes appended (in no triangle).
TriMesh with_chordae_nodes(const TriMesh& mesh, const ChordaeAttachment& attachment);

}  // namespace valve
