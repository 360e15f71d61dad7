#pragma once
// Contact as a conservative potential on the distance between surfaces: the default contact
// model, with two potentials (below: the cubic penalty, and the log barrier of Incremental
// Potential Contact for the quasi-static solver). The seed's Eq. 4.5 (contact.hpp) stays
// selectable for reproduction.
//
// Barrier (Li et al. 2020, "Incremental Potential Contact"; codimensional IPC, Li et al.
// 2021, for thin sheets): with s = d − ξ the distance less an offset ξ (e.g. the leaflet
// thickness: mid-surfaces then stay ξ apart) and ŝ = δ the barrier's reach,
//     E = Σ_pairs κ b(s),  b(s) = −(s − ŝ)² ln(s / ŝ) for 0 < s < ŝ, 0 for s >= ŝ, ∞ for s <= 0,
//     b'(s) = −2 (s − ŝ) ln(s/ŝ) − (s − ŝ)²/s,  b''(s) = −2 ln(s/ŝ) − 4 (s − ŝ)/s + (s − ŝ)²/s²,
// so the force −κ b'(s) grows without bound as s → 0: no pair ever reaches d = ξ. The
// Jacobian is the pair's whole Hessian κ (b''(s) ∇d ∇dᵀ + b'(s) ∇²d), projected to positive
// semi-definite (its eigenvalues clamped at 0, found within the at most 5-dimensional span
// that holds its range), as IPC does: the Gauss–Newton part alone left the quasi-static solver
// converging linearly where pressed pairs slide (1,221 iterations on the sample mitral
// closure); near equilibrium the quasi-static solver asks for
// the exact Hessian instead (set_jacobian_mode). Its gradient is exact (the envelope theorem, as
// below); ∇²d is in closed form for each closest feature (face, edge, vertex), and from
// central differences of the gradient (step 1e-6 mm) where that does not hold (d ≈ 0,
// parallel edges). The step bound (step_ratio) keeps every candidate pair's gap d − ξ above
// zero along the step, so no iterate ever intersects (a line search only shortens steps).
// Two conservative continuous collision bounds, the larger step of the two: the
// supporting-plane bound below (a pair's closing below 0.8 (d − ξ): the gap keeps 0.2 of its
// start), and for the pairs that bound would cut, additive CCD along the step (codimensional
// IPC's Algorithm 1): the distance measured again after each advance of 0.9 (d − ξ) over the
// pair's relative motion, stopping before a measured gap below 0.2 of the start's (between
// measurements the gap keeps a tenth of the last one). The plane bound counts a triangle's
// tilt at its farthest node as closing, so with it alone a face hinging or sliding past a
// node a tenth of a millimetre away holds every step to that tenth; on the sample mitral
// closure the limiting pair's distance along such steps often never fell. With both, the
// aortic valve FE closure takes 59 Newton iterations against 121, the sample mitral closure
// 97 against 153 (medians over eleven starts, measured with directions factorised by an LDLᵀ;
// docs/methods/contact.md).
//
// Why not the seed's law by default: it acts on nodes in front of a triangle only, with no
// reaction, and cancels only the pressure on the node. On the 3-leaflet aortic valve the
// free edges meet edge-on at the centre; a free-edge node that slips past a neighbour's
// free edge has no triangle in front of it and the leaflets pass through each other
// (measured: every free edge 1.8 mm past the valve axis). Leaflet tension, which Eq. 4.5
// does not cancel, pulls coapting nodes through as well.
//
// Energy. With d the unsigned distance between the closest points of two primitives and
// δ the separation kept between surfaces (default 0.25 mm: touching leaflets end up well
// inside the seed's 0.5 mm coaptation threshold),
//
//     E = Σ_pairs k (δ − d)³ / (3 δ)   for d < δ,  0 otherwise,
//
// so the force k (δ − d)² / δ and its stiffness 2 k (δ − d) / δ both start from zero at
// d = δ and reach k δ and 2 k at d = 0. Why not a quadratic energy (force k (δ − d)): a
// pair that enters contact between two Jacobian evaluations then acts with its full
// stiffness explicitly, and BDF2 chatters at 0.002 mm per step on two sheets pressed
// together instead of settling; with the cubic it settles.
//
// Pairs: (1) node p vs triangle t, q = Σ w_j x_j the closest point of t to p (on its face,
// an edge or a vertex); (2) a boundary edge (free edge) vs any other edge, q the closest
// points of the two segments (ends included): free edges meet the neighbours edge-on, where
// no node need be near any face; (3) with interior_edges, every edge vs every edge. Two
// sheets can pass through each other edge through edge while no node comes near a face
// (blades crossing): on the closed three-leaflet aortic valve 34 (FE) and 44 (M-S) pairs
// of triangles of different leaflets crossed at the centre without it, none with it
// (analysis/surface_intersections.hpp counts them); on the sample mitral closures 17-29
// pairs crossed at the commissures without it, none with it. It costs pairs: the sample
// mitral closure took 1.03 s against 0.85 s, and 0.93 s with the detection distance cut to
// 2.5 mm (the mitral scene's setting), so it stays a scene option. Excluded and narrow pairs: see
// ContactTopology. Every other pair closer than δ acts (a narrow pair within its own reach),
// so the total energy and force are continuous in the positions.
// Why not only the nearest triangle per node and leaflet: a node in a valley between two
// faces meeting at an angle switches between them, its force turns by that angle in one
// step, and BDF2 locks into a 2-cycle (measured on the sample mitral closure: node 210
// alternated each step between two faces 60° apart, the closure never came to rest; 4,552
// steps, residual 0.05, 58 s; with every pair: 968 steps, residual 1.1e-4, 13.9 s). The price: a node over a shared edge or vertex is pushed by each of its
// triangles, up to ~6x the stiffness over a face centre; with k δ = 0.25 N against ~0.02 N
// of pressure per node this moves the resting separation by a few hundredths of a mm.
//
// Forces, exact by the envelope theorem (q minimises the distance): with n = (p − q)/d and
// g = k (δ − d)² / δ,
//     f_p = g n,   f_j = −g w_j n   (edge pairs: weights 1 − s, s, −(1 − t), −t).
// Every action has its reaction, so the term conserves momentum and energy.
// Jacobian: Gauss–Newton, df/dx ≈ −g' ∇d ∇dᵀ with g' = 2 k (δ − d) / δ and ∇d = (n, −w_j n).
// It drops g ∇²d,
// the rotation of n, which is what keeps it negative semi-definite (a symmetric positive
// system matrix for CHOLMOD) and is exact for a node over the face of a fixed triangle.
//
// Detection (a Verlet list). Candidates are the pairs closer than the detection distance D
// when the list is built; D = δ + 4 L with the step bound L = max(δ, half the mean rest
// edge length) by default, at most max_detection where a scene caps it (the mitral scene
// at 2.5 mm: its ~650-triangle membrane closes fastest there, finer meshes take their own
// smaller D). The list is rebuilt at a coupling refresh (every Jacobian
// evaluation) once some node has moved more than L since the last build, and a step may
// take no node further than 2L from where the list was built (step_ratio): a pair outside
// the list has then closed in by at most 2 · 2L = D − δ, so none comes within δ unseen.
// Right after a rebuild a node may so move 2L in one step (with a flat L per step, the
// sample mitral closure's step size was set by L on every step of the closing motion).
// The Jacobian pattern holds only pairs
// that were active (d < δ) at some Jacobian evaluation, so a generous D costs distance
// queries, not fill-in. Since d is unsigned, a surface that was crossed stays crossed, so
// no candidate pair may close in one step by its whole distance (step_ratio): every
// candidate pair's closing
//     c = max_j n · (Δx_j − Δp)  <  0.8 max(δ, d),   d, n at the step's start,
// for node p and triangle (x_1, x_2, x_3), n = (p − q)/d the unit vector from the closest
// point q; for two edges, the largest over their four end-node pairs. Why this bounds d':
// q is the closest point of a convex set, so n · (p − x) ≥ d for every point x = Σ w_j x_j
// of the triangle (the supporting plane), and with w' the closest point's weights after
// the step,
//     d' ≥ n · (p' − Σ w'_j x'_j) ≥ d + Σ w'_j n · (Δp − Δx_j) ≥ d − c,
// and likewise at every point of the straight path (edges: the Minkowski difference of two
// segments is convex, and the closing is bilinear in the two parameters). A pair at
// distance d ≥ δ so closes by at most 0.8 d and cannot reach the other side; a pair inside
// δ closes by at most 0.8 δ, which does not rule out a crossing below 0.8 δ: there the
// penalty, whose stiffness is well above the applied load (k δ ≫ pressure × node area),
// keeps pairs from closing that fast (measured: with steps up to 0.6 mm, sheets pressed
// together crossed). Sliding along n's plane costs nothing. Where d vanishes (no n), the
// bound is max_j |Δx_j − Δp|. Why not an absolute bound: keeping every node of a pair within
// 0.4 max(δ, d) of where it started holds two coapting leaflets moving together to 0.1 mm
// per step; measured on the sample mitral closure: 263 steps with that bound, 188 bounding
// the relative motion max_j |Δx_j − Δp| instead (still held on 108 steps by pairs inside δ
// sliding past each other), 159 with the closing along n.
#include <algorithm>
#include <vector>

#include "valve/mechanics/broad_phase.hpp"
#include "valve/mechanics/contact_base.hpp"

namespace valve {

enum class ContactPotential { penalty, barrier };
/// The barrier's default κ, N/mm (100 N/m): its log grows without bound near contact, so it
/// needs less stiffness than the penalty's k to hold the same loads.
inline constexpr double kDefaultBarrierStiffness = 0.1;

struct PenaltyContactOptions {
  ContactPotential potential = ContactPotential::penalty;
  double offset = 0;         // mm, ξ (barrier): the distance kept between mid-surfaces at s = 0
  double separation = 0.25;  // mm, δ (barrier: its reach ŝ beyond the offset)
  double stiffness = 1.0;    // N/mm, k (1000 N/m): the force at d = 0 is k δ (barrier: κ)
  double detection = 0;      // mm, D; 0: δ + 4 max(δ, mean edge / 2)
  double max_detection = 0;  // mm: caps the automatic D (detection 0); 0: no cap
  bool between_leaflets = true;
  bool self_contact = true;
  bool edge_contact = true;     // boundary-edge vs edge pairs
  bool interior_edges = false;  // with edge_contact: every edge vs every edge (pairs (3))
  BroadPhaseMethod broad_phase = BroadPhaseMethod::spatial_hash;
  void validate() const;  // throws InputError (also: interior_edges without edge_contact)
};

class PenaltyContactTerm final : public ContactForceTerm {
 public:
  /// Pairs whose nodes are all constrained (per dof flags) are skipped.
  PenaltyContactTerm(const TriMesh& mesh, const PenaltyContactOptions& opt, const std::vector<char>& constrained);
  std::string name() const override { return "contact"; }
  void couplings(std::vector<std::pair<int, int>>& pairs) const override;
  bool update_couplings(const VecX& x) override;
  double max_step_length() const override { return std::min(verlet_step(), 0.4 * opt_.separation); }
  ContactPotential potential() const { return opt_.potential; }
  double step_ratio(const VecX& x, const VecX& dx) const override;
  /// The barrier's pair Hessians projected (default) or exact; the penalty's is always its
  /// Gauss–Newton part.
  void set_jacobian_mode(JacobianMode mode) override { jacobian_mode_ = mode; }
  /// The pairs within the barrier's reach where the solve starts: those of one leaflet are
  /// excluded, as at rest; those of two leaflets (a commissure's sides, 0.004 mm apart on the
  /// distended root wall) become narrow pairs, whose offset and reach shrink by
  /// narrowing(start gap) so that they act only within half the gap they start with.
  void start_at(const VecX& x) override;
  void add(const State& s, VecX& f, BlockJacobian* dfdx, BlockJacobian* dfdv) const override;
  bool energy(const State& s, double& e) const override;

  const ContactStatistics& statistics() const override { return stats_; }
  double detection_distance() const override { return detection_; }

 private:
  /// An active pair: its four nodes (node + triangle, or two edges), their weights
  /// (∇d = weight · n per node), the unit normal n and the distance.
  struct Contact {
    int nodes[4];
    double weights[4];
    Vec3 normal;
    double distance;
    bool edge = false;  // two edges (else node and triangle)
    double scale = 1;   // the pair's narrowing (pair_scale_)
  };
  using PairVector = Eigen::Matrix<double, 12, 1>;
  using PairMatrix = Eigen::Matrix<double, 12, 12>;
  /// The pair's energy gradient over its four nodes' coordinates at positions `y`.
  PairVector pair_gradient(bool edge, const PairVector& y, double scale) const;
  /// The barrier pair's Hessian, projected to positive semi-definite (below) unless the
  /// Jacobian mode is exact.
  PairMatrix projected_pair_hessian(const Contact& c, const VecX& x) const;
  /// Central differences of pair_gradient, where the distance's closed-form Hessian does not hold.
  void pair_hessian_by_differences(bool edge, const PairVector& y, double scale, PairMatrix& H) const;
  /// A candidate pair's distance d and unit direction n from the second side (triangle, or
  /// the other edge) to the first (node, or query edge); n = 0 when d vanishes. A pair that
  /// cannot be within reach is not measured: its `distance` is then a lower bound (its
  /// distance when the candidate list was built, less its nodes' largest moves since).
  struct PairGap {
    double distance;
    Vec3 normal;
    bool lower_bound = false;
  };
  /// The gap of candidate pair k (face pairs, then edge pairs) measured at x.
  PairGap measured_gap(size_t k, const VecX& x) const;
  /// Candidate pair k's nodes: the node and its triangle's three, or two edges' two each; true
  /// for an edge pair.
  bool pair_nodes(size_t k, int (&nodes)[4]) const;
  /// Also records, where given, every candidate pair's gap (face pairs, then edge pairs).
  void active_contacts(const VecX& x, std::vector<Contact>& out, std::vector<PairGap>* gaps = nullptr) const;
  /// The active contacts at x: those found by the last update_couplings if x is where it
  /// ran (a Jacobian evaluation asks twice at one state), else computed afresh into `scratch`.
  const std::vector<Contact>& contacts_at(const VecX& x, std::vector<Contact>& scratch) const;
  /// Whether update_couplings last found the active contacts at x.
  bool contacts_found_at(const VecX& x) const { return contacts_x_.size() == x.size() && contacts_x_ == x; }
  void rebuild_candidates(const VecX& x);
  /// Largest node motion the candidate list tolerates before a rebuild: (D − δ − ξ)/4.
  double verlet_step() const { return 0.25 * (detection_ - reach()); }
  /// Pairs closer than this act: δ (penalty) or ξ + ŝ (barrier).
  double reach() const { return opt_.separation + (barrier() ? opt_.offset : 0.0); }
  bool barrier() const { return opt_.potential == ContactPotential::barrier; }
  /// The potential per pair at distance d, its force magnitude −dE/dd and that's slope −d²E/dd²,
  /// with the offset and reach times `scale` (a narrow pair's narrowing, else 1).
  double pair_energy(double d, double scale) const;
  void pair_force(double d, double scale, double& magnitude, double& slope) const;
  /// A pair's scale from its start gap (ContactTopology::start_gap): 1 for 0 (not a narrow
  /// pair), else start gap / (2 (ξ + ŝ)), at most 1.
  double narrowing(double start_gap) const;

  PenaltyContactOptions opt_;
  ContactTopology topology_;
  double detection_;
  std::vector<char> constrained_node_;
  std::vector<int> query_edges_;     // indices into edges(): the boundary edges, or all with
                                     // interior_edges; empty without edge contact
  std::vector<std::pair<int, int>> face_pairs_;        // (node, triangle) candidates, sorted
  std::vector<std::pair<int, int>> edge_pairs_;        // (query edge, edge) candidates
  std::vector<double> built_distance_;                 // each candidate's distance at built_at_
  std::vector<double> pair_scale_;                     // each candidate's narrowing (1: none)
  std::vector<std::pair<int, int>> coupled_;
  VecX built_at_;  // positions when the candidate list was built (empty: never)
  VecX contacts_x_;                 // where update_couplings last found the active contacts
  std::vector<Contact> contacts_;   // and what it found
  std::vector<PairGap> pair_gaps_;  // there: each candidate pair's gap (face, then edge pairs)
  mutable ContactStatistics stats_;
  JacobianMode jacobian_mode_ = JacobianMode::projected;
};

}  // namespace valve
