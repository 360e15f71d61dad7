#pragma once
// Contact between leaflets and within a leaflet (seed 4.2.3, Eq. 4.5).
//
// A free node p in front of a triangle t (its projection on t's plane falls inside t) at
// signed distance d = m·(p − x_a) receives the force f_p = g(d, F) m, where m = s n is
// t's unit normal n oriented toward the side s the node came from, and F is the part of
// the node's external force that drives it toward t, F = max(0, −m·f_ext):
//
//     g = F exp(−k d / F) τ(d / z)   for 0 <= d < z,      g = F − k_p d   for d < 0,
//
// k the contact stiffness (seed 10 N/m), z the zone width (seed 0.1 mm), k_p the penalty
// past the surface. Inside the zone the contact cancels the push of the pressure; past the
// surface a linear penalty takes over. Departures from the seed:
//  - the seed cuts the force off at d = z, where it jumps from ≈ F to 0 (F ≫ k z at
//    80 mmHg), and a static solver then chatters across the zone edge. τ(u) = 1 − 3u² + 2u³
//    brings g to 0 with zero slope at d = z.
//  - k_p is its own option (default: the seed's k). In a static solution leaflet tension,
//    not only the pressure that g cancels, pulls free-edge nodes into a neighbour: on the
//    3-leaflet valve at 80 mmHg, 10 N/m let them through by up to 1.8 mm.
//
// As in the seed the force acts on the node only (no reaction on the triangle): each
// coapting node balances its own pressure. Per node and per neighbouring leaflet only the
// nearest triangle in front acts, so a node over a shared edge is not pushed twice.
//
// Between leaflets the seed's rule applies by default: s = +1, the side the normal points
// to (the ventricular faces coapt), so a free edge that slips past a neighbour's is pushed
// back to the front. Otherwise (self-contact, or the option off) the side s of each
// (node, triangle) pair is fixed when the pair enters the candidate
// set (|d| below the detection distance) and kept while it stays there, so a node pushed
// slightly through a sheet is pushed back, not across. Solvers keep each step below
// max_step_length() so that no node can cross the detection slab unseen.
//
// Jacobian: with r = p − x_a, P = s (I − n nᵀ) / |c| (c = e1 × e2 the area vector) and
// dc/dx_v the cross-product matrices of the pressure term, dm/dx_v = P dc/dx_v and
//     df/dp   = g_d m mᵀ
//     df/dx_v = m (g_d (rᵀ dm/dx_v − [v = a] mᵀ) − g_F f_extᵀ dm/dx_v) + g dm/dx_v.
// The dependence of f_ext on positions (follower pressure) is left out of the Jacobian.
#include <map>
#include <string>
#include <vector>

#include "valve/mechanics/broad_phase.hpp"
#include "valve/mechanics/contact_base.hpp"
#include "valve/mesh/tri_mesh.hpp"

namespace valve {

struct ContactOptions {
  double stiffness = 0.01;  // N/mm (seed: 10 N/m)
  double penetration_stiffness = 0.01;  // N/mm past the surface (seed: = stiffness)
  double zone = 0.1;        // mm
  bool between_leaflets = true;
  bool self_contact = true;
  /// Seed: between leaflets, "in front" is always the side the normal points to (the
  /// ventricular faces coapt). Off: each pair keeps the side the node came from.
  bool normal_side_between_leaflets = true;
  /// Candidate pairs are kept within this distance of a triangle (0: zone + mean edge length).
  double detection = 0;
  double max_detection = 0;  // mm: caps the automatic distance (detection 0); 0: no cap
  BroadPhaseMethod broad_phase = BroadPhaseMethod::spatial_hash;
  /// Smallest projection barycentric coordinate still counted as "in front" of a triangle;
  /// slightly negative so nodes over an edge or a crease are not let through.
  double inside_tolerance = -0.02;
  void validate() const;  // throws InputError
};

class ContactTerm final : public ContactForceTerm {
 public:
  /// `external` are the scene's external-load terms (their sum is f_ext); they must outlive
  /// this term. Nodes constrained in `constrained` (per dof) get no contact force.
  ContactTerm(const TriMesh& mesh, const ContactOptions& opt, std::vector<const ForceTerm*> external,
              const std::vector<char>& constrained);
  std::string name() const override { return "contact"; }
  void couplings(std::vector<std::pair<int, int>>& pairs) const override;
  bool update_couplings(const VecX& x) override;
  double max_step_length() const override { return 0.5 * (detection_ - opt_.zone); }
  void add(const State& s, VecX& f, BlockJacobian* dfdx, BlockJacobian* dfdv) const override;

  const ContactStatistics& statistics() const override { return stats_; }
  double detection_distance() const override { return detection_; }

 private:
  struct Candidate {
    int node, triangle;
    int side;  // +1, −1, or 0 while undecided (|d| too small to tell)
  };
  ContactOptions opt_;
  ContactTopology topology_;
  double detection_;
  std::vector<char> query_;                   // free nodes
  std::vector<const ForceTerm*> external_;
  std::vector<Candidate> candidates_;         // sorted by (node, triangle)
  std::vector<std::pair<int, int>> coupled_;  // (node, triangle vertex) of the candidates
  mutable ContactStatistics stats_;
};

}  // namespace valve
