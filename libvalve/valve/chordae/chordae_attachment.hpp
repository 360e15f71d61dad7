#pragma once
// Puts a chordae network on a leaflet mesh for simulation (seed 5.2.2): insertions become
// the mesh nodes they are snapped to, papillary tips and branch points become extra nodes
// appended after the mesh nodes (tips fixed, branch points free, with the chords' mass),
// and every segment becomes a tension-only rod.
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
};

struct ChordaeAttachment {
  int mesh_nodes = 0;             // nodes 0..mesh_nodes-1 are the leaflets'
  std::vector<int> point_node;    // system node of every network point
  MatX3 extra_points;             // papillary tips and branch points, in network order
  std::vector<NodeRole> extra_roles;
  std::vector<double> extra_mass;  // g: half of each adjoining chord's mass
  std::vector<Rod> rods;           // one per segment, in network order
};

/// Builds the rods (law and section as ChordMaterial says, rest length from
/// ChordaeNetwork::rest_length) for a network whose insertions are snapped to a mesh of
/// `mesh_nodes` nodes.
ChordaeAttachment attach_chordae(const ChordaeNetwork& network, int mesh_nodes, const ChordMaterial& material);

/// The mesh with the attachment's extra nodes appended (in no triangle).
TriMesh with_chordae_nodes(const TriMesh& mesh, const ChordaeAttachment& attachment);

}  // namespace valve
