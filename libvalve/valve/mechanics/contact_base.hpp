#pragma once
// What the two contact models (contact.hpp: the seed's Eq. 4.5; penalty_contact.hpp: a
// conservative penalty) share: which primitives may touch, the statistics they report and
// the interface a stage reads them through.
//
// ContactTopology: the part of contact detection that depends only on connectivity.
// A node never touches a triangle that shares a vertex with the node's 1-ring: at a sharp
// bend such triangles lie within any contact distance without touching. With a rest reach
// (the barrier), only incident primitives (a node and its own triangles, edges sharing a
// node) and pairs of one leaflet within that reach in the mesh's rest shape (neighbours at a
// sharp bend) or where it starts are excluded. Pairs of two leaflets within the reach where
// the mesh starts (leaflets meeting along a commissure, 0.004 mm apart on the distended
// aortic root) are narrow pairs: their start gap d₀ is remembered (the smallest distance seen
// where a solve may start: the rest shape when the mesh gives no start shape, and each
// start_at), and the barrier acts on them within half of it (penalty_contact.hpp); excluded,
// such sides hinged through each other. Those that start touching (closer than
// kTouchingFraction of the reach) are excluded. Pairs
// of two leaflets are judged by the start shape only, where the mesh gives one: a graft's
// rest shape is its own cut shape, placed apart from the others. The other neighbours push
// back when a fold brings them together, so a sheet cannot fold through itself. Pairs on the same
// leaflet are self-contact, pairs on different leaflets contact between leaflets; a node
// on two leaflets (commissure corner) counts as between leaflets.
#include <array>
#include <utility>
#include <vector>

#include "valve/mechanics/force_term.hpp"
#include "valve/mesh/tri_mesh.hpp"

namespace valve {

struct ContactStatistics {
  long candidate_updates = 0;
  long candidate_pairs = 0;        // at the last update
  long narrow_pairs = 0;           // pairs of two leaflets that start within the barrier's reach
                                   // (ContactTopology::narrow_pairs)
  long active_pairs = 0;           // pairs exerting a force at the last evaluation
  double broad_phase_seconds = 0;
  double deepest_penetration = 0;  // mm at the last evaluation; see each model for its meaning
  double closest_distance = -1;    // mm, smallest distance of an active pair (-1: none)
};

/// Adds the node pairs `added` (any order, duplicates allowed) to the sorted Jacobian
/// pattern `pattern` and returns whether it grew. The pattern only grows: stale couplings
/// cost a few zeros, and keeping them spares a symbolic re-analysis whenever a pair leaves
/// contact.
bool grow_couplings(std::vector<std::pair<int, int>>& pattern, std::vector<std::pair<int, int>> added);

/// A force term that detects contact; stages report its statistics.
class ContactForceTerm : public ForceTerm {
 public:
  virtual const ContactStatistics& statistics() const = 0;
  /// Pairs closer than this are candidates between two coupling updates (mm).
  virtual double detection_distance() const = 0;
};

class ContactTopology {
 public:
  /// `rest_reach` < 0: the 1-ring rule; >= 0: incidence, and pairs within it at rest.
  ContactTopology(const TriMesh& mesh, bool self_contact, bool between_leaflets, double rest_reach = -1);

  /// With a rest reach: the pairs within it at positions x (where a solve starts, e.g. after
  /// the aortic root's distension has brought two leaflets' attachments within it), or with
  /// `within_leaflets_only` only those of one leaflet. Pairs of one leaflet are excluded; pairs
  /// of two leaflets are kept as narrow pairs (start_gap) unless they start closer than
  /// kTouchingFraction of the reach (touching or overlapping: excluded). No-op under the
  /// 1-ring rule.
  void exclude_close_at(const VecX& x, bool within_leaflets_only = false);

  /// Pairs of two leaflets that start closer than this fraction of the rest reach are
  /// excluded: their own gap is too small to act on.
  static constexpr double kTouchingFraction = 1e-3;

  /// True when node `node` must not interact with triangle `triangle`.
  bool excluded(int node, int triangle) const;
  /// True when edge e1 must not interact with edge e2 (indices into edges()): they share a
  /// vertex or one edge's vertex is in the other's 1-ring, or the leaflet rule excludes them.
  bool excluded_edges(int e1, int e2) const;
  /// A narrow pair's distance where it started within the rest reach (the smallest of the
  /// starts seen); 0 for every other pair.
  double start_gap(int node, int triangle) const;
  double start_gap_edges(int a, int b, int c, int d) const;
  /// Narrow pairs recorded, (node, triangle) and edge pairs; those whose nodes are all held,
  /// or that the leaflet rule or a touching start excludes, among them.
  long narrow_pairs() const { return static_cast<long>(narrow_faces_.size() + narrow_edges_.size()); }
  bool on_leaflet(int node, int leaflet) const;
  /// Whether the node belongs to any triangle (isolated nodes, such as chord points, never
  /// touch anything).
  bool has_triangles(int node) const { return triangle_nodes_[node] != 0; }
  /// has_triangles for every node: the nodes a broad phase queries.
  const std::vector<char>& triangle_nodes() const { return triangle_nodes_; }

  const std::vector<Tri>& triangles() const { return triangles_; }
  int leaflet_of(int triangle) const { return leaflet_[triangle]; }
  /// Mean rest edge length (mm); 0 for a mesh without edges.
  double mean_edge_length() const { return mean_edge_; }
  /// All edges (a < b), sorted.
  const std::vector<std::pair<int, int>>& edges() const { return edges_; }
  /// Per edge: 1 when it has only one triangle (free edges and attached boundaries).
  const std::vector<char>& boundary_edge() const { return boundary_edge_; }

 private:
  bool incidence_only() const { return rest_reach_ >= 0; }
  bool in_ring(int node, int other) const;
  bool same_leaflet(int node, int triangle) const;
  bool same_leaflet_edges(int a, int b, int c, int d) const;
  bool leaflet_rule_excludes(int node, int leaflet) const;

  bool close_at_rest(int node, int triangle) const;
  bool edges_close_at_rest(int e1, int e2) const;

  bool self_, between_;
  double rest_reach_ = -1;                               // < 0: the 1-ring rule
  // Pairs within it at rest or the start, as sorted lists: per node its triangles, per edge
  // the higher-numbered edges (the candidate lists ask once per pair, millions of times).
  std::vector<std::vector<int>> rest_close_faces_;
  std::vector<std::vector<int>> rest_close_edges_;
  std::vector<std::pair<std::pair<int, int>, double>> narrow_faces_;     // (node, triangle), start gap; sorted
  std::vector<std::pair<std::array<int, 4>, double>> narrow_edges_;      // (a, b, c, d), a < b, c < d, (a, b) < (c, d), start gap; sorted
  std::vector<Tri> triangles_;
  std::vector<int> leaflet_;                     // per triangle
  std::vector<std::vector<int>> node_leaflets_;  // sorted
  std::vector<std::vector<int>> ring_;           // sorted 1-ring incl. the node
  std::vector<char> triangle_nodes_;             // has_triangles per node
  std::vector<std::pair<int, int>> edges_;
  std::vector<char> boundary_edge_;
  double mean_edge_ = 0;
};

}  // namespace valve
