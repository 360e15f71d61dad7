#include "valve/mechanics/penalty_contact.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "valve/core/error.hpp"
#include "valve/core/parallel.hpp"
#include "valve/mesh/closest_point.hpp"

namespace valve {

void PenaltyContactOptions::validate() const {
  if (!(separation > 0)) throw InputError("contact.separation: expected > 0 mm, found " + std::to_string(separation));
  if (!(offset >= 0)) throw InputError("contact.offset: expected >= 0 mm, found " + std::to_string(offset));
  if (offset > 0 && potential != ContactPotential::barrier)
    throw InputError("contact.offset: expected 0 for the penalty model (the barrier keeps an offset), found " +
                     std::to_string(offset) + " mm");
  if (!(stiffness > 0)) throw InputError("contact.stiffness: expected > 0, found " + std::to_string(stiffness));
  if (detection != 0 && !(detection > separation + offset))
    throw InputError("contact.detection: expected 0 (automatic) or more than the separation (plus the offset)");
  if (max_detection != 0 && !(max_detection > separation + offset && detection == 0))
    throw InputError("contact.max_detection: expected 0, or more than the separation (plus the offset) with detection 0");
  if (!between_leaflets && !self_contact)
    throw InputError("contact: expected between_leaflets or self_contact (or both) to be true");
  if (interior_edges && !edge_contact)
    throw InputError("contact.interior_edges: expected false when edges is false, found true");
}

PenaltyContactTerm::PenaltyContactTerm(const TriMesh& mesh, const PenaltyContactOptions& opt,
                                       const std::vector<char>& constrained)
    : opt_(opt),
      topology_(mesh, opt.self_contact, opt.between_leaflets,
                opt.potential == ContactPotential::barrier ? opt.offset + opt.separation : -1.0) {
  opt_.validate();
  detection_ = opt_.detection != 0 ? opt_.detection
                                   : reach() + 4 * std::max(opt_.separation, 0.5 * topology_.mean_edge_length());
  if (opt_.max_detection != 0) detection_ = std::min(detection_, opt_.max_detection);
  const int n = mesh.num_nodes();
  constrained_node_.assign(n, 0);
  for (int i = 0; i < n; ++i) constrained_node_[i] = constrained[3 * i];
  if (opt_.edge_contact)
    for (size_t e = 0; e < topology_.edges().size(); ++e)
      if (opt_.interior_edges || topology_.boundary_edge()[e]) query_edges_.push_back(static_cast<int>(e));
}

double PenaltyContactTerm::narrowing(double start_gap) const {
  return start_gap > 0 ? std::min(1.0, start_gap / (2 * reach())) : 1.0;
}

void PenaltyContactTerm::start_at(const VecX& x) {
  topology_.exclude_close_at(x);
  // The candidate list, its gaps and the contacts found honour the new exclusions and narrow
  // pairs from the next build on.
  built_at_.resize(0);
  contacts_x_.resize(0);
  pair_gaps_.clear();
}

void PenaltyContactTerm::couplings(std::vector<std::pair<int, int>>& pairs) const {
  pairs.insert(pairs.end(), coupled_.begin(), coupled_.end());
}

bool PenaltyContactTerm::update_couplings(const VecX& x) {
  bool stale = built_at_.size() != x.size();
  for (int i = 0; !stale && i < x.size() / 3; ++i) stale = (node3(x, i) - node3(built_at_, i)).norm() > verlet_step();
  if (stale) rebuild_candidates(x);
  // A second Jacobian at the same state (the projected one beside the exact) finds what the
  // first found.
  else if (contacts_found_at(x))
    return false;
  // The pattern needs the pairs active here, where the Jacobian is evaluated; the step
  // limits need every candidate's distance here, where the solver's step starts.
  active_contacts(x, contacts_, &pair_gaps_);
  contacts_x_ = x;
  std::vector<std::pair<int, int>> coupled;
  for (const Contact& c : contacts_)
    for (int j = 0; j < 4; ++j)
      for (int l = j + 1; l < 4; ++l) coupled.emplace_back(std::min(c.nodes[j], c.nodes[l]), std::max(c.nodes[j], c.nodes[l]));
  return grow_couplings(coupled_, std::move(coupled));
}

const std::vector<PenaltyContactTerm::Contact>& PenaltyContactTerm::contacts_at(const VecX& x,
                                                                                 std::vector<Contact>& scratch) const {
  if (contacts_found_at(x)) return contacts_;
  active_contacts(x, scratch);
  return scratch;
}

void PenaltyContactTerm::rebuild_candidates(const VecX& x) {
  built_at_ = x;
  const auto t0 = std::chrono::steady_clock::now();
  const auto& tris = topology_.triangles();
  const auto& edges = topology_.edges();
  auto all_constrained = [&](std::initializer_list<int> nodes) {
    for (int v : nodes)
      if (!constrained_node_[v]) return false;
    return true;
  };

  // The exact distances of the broad phase's candidates, in chunks (core/parallel.hpp): a
  // candidate dropped gets a negative distance, and the kept ones are gathered in order.
  auto measure = [&](const auto& candidates, auto distance_of) {
    std::vector<double> distance(candidates.size());
    for_each_chunk(candidates.size(), chunks_for(candidates.size()), [&](size_t, size_t begin, size_t end) {
      for (size_t k = begin; k < end; ++k) distance[k] = distance_of(candidates[k]);
    });
    return distance;
  };
  face_pairs_.clear();
  built_distance_.clear();
  pair_scale_.clear();
  const auto face_candidates = broad_phase_pairs(x, tris, detection_, opt_.broad_phase, topology_.triangle_nodes());
  const auto face_distance = measure(face_candidates, [&](const std::pair<int, int>& pair) {
    const auto& [i, t] = pair;
    const Tri& tri = tris[t];
    if (topology_.excluded(i, t) || all_constrained({i, tri[0], tri[1], tri[2]})) return -1.0;
    const double d = point_triangle_distance(node3(x, i), node3(x, tri[0]), node3(x, tri[1]), node3(x, tri[2]));
    return d <= detection_ ? d : -1.0;
  });
  for (size_t k = 0; k < face_candidates.size(); ++k)
    if (face_distance[k] >= 0) {
      face_pairs_.push_back(face_candidates[k]), built_distance_.push_back(face_distance[k]);
      pair_scale_.push_back(narrowing(topology_.start_gap(face_candidates[k].first, face_candidates[k].second)));
    }

  edge_pairs_.clear();
  if (opt_.edge_contact) {
    const auto edge_candidates = edge_box_pairs(x, edges, query_edges_, detection_);
    const auto edge_distance = measure(edge_candidates, [&](const std::pair<int, int>& pair) {
      if (topology_.excluded_edges(pair.first, pair.second)) return -1.0;
      const auto [a, b] = edges[pair.first];
      const auto [c, d] = edges[pair.second];
      if (all_constrained({a, b, c, d})) return -1.0;
      const double distance = segment_segment_distance(node3(x, a), node3(x, b), node3(x, c), node3(x, d));
      return distance <= detection_ ? distance : -1.0;
    });
    for (size_t k = 0; k < edge_candidates.size(); ++k)  // after every face pair's
      if (edge_distance[k] >= 0) {
        edge_pairs_.push_back(edge_candidates[k]), built_distance_.push_back(edge_distance[k]);
        const auto [a, b] = edges[edge_candidates[k].first];
        const auto [c, d] = edges[edge_candidates[k].second];
        pair_scale_.push_back(narrowing(topology_.start_gap_edges(a, b, c, d)));
      }
  }

  ++stats_.candidate_updates;
  stats_.candidate_pairs = static_cast<long>(face_pairs_.size() + edge_pairs_.size());
  stats_.narrow_pairs = topology_.narrow_pairs();
  stats_.broad_phase_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

namespace {

// The closest points of a pair: node p0 and triangle (p1, p2, p3), or edges (p0, p1) and
// (p2, p3). `diff` runs from the second side's closest point to the first's; ∇d = w_j n per node.
struct PairGeometry {
  Vec3 diff;
  double weights[4];
};
using PairVector12 = Eigen::Matrix<double, 12, 1>;
using PairMatrix12 = Eigen::Matrix<double, 12, 12>;

PairGeometry pair_geometry(bool edge, const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3) {
  PairGeometry g;
  if (edge) {
    const auto [s, u] = closest_segment_parameters(p0, p1, p2, p3);
    g.diff = (p0 + s * (p1 - p0)) - (p2 + u * (p3 - p2));
    g.weights[0] = 1 - s, g.weights[1] = s, g.weights[2] = -(1 - u), g.weights[3] = -u;
  } else {
    const Vec3 w = closest_point_weights(p0, p1, p2, p3);
    g.diff = p0 - (w[0] * p1 + w[1] * p2 + w[2] * p3);
    g.weights[0] = 1, g.weights[1] = -w[0], g.weights[2] = -w[1], g.weights[3] = -w[2];
  }
  return g;
}

// Gradient and Hessian of a pair's distance d = |D|, D = Σ c_j x_j (PairGeometry's diff and
// weights), over the pair's 12 coordinates. The closest points minimise ½|D|² over the
// parameters a of the closest feature (the weights strictly inside their bounds: s and u of two
// edges, the nonzero barycentric weights of a triangle point); eliminating them gives, with
// C = [c_j I] (3×12), T_i = Σ_j e_ij x_j the feature's tangents (e_i = ∂c/∂a_i) and
// G_i = [e_ij D + c_j T_i]_j (12),
//     ∇(½d²) = Cᵀ D,   ∇²(½d²) = CᵀC − G (TᵀT)⁻¹ Gᵀ   (the Schur complement),
//     ∇d = Cᵀ D / d,   ∇²d = (∇²(½d²) − ∇d ∇dᵀ) / d.
// Both lie in the span of Cᵀ's 3 columns and G's m (at most 5 of the 12 dimensions): `range`,
// where given, gets an orthonormal basis of that span (zero columns past it), in which the
// Hessian's projection to positive semi-definite costs a 5 × 5 eigenproblem instead of a
// 12 × 12 one.
// False where that does not hold: d ≈ 0, or a feature whose tangents are dependent
// (parallel edges, a degenerate triangle: the closest points are not unique there).
using PairRange = Eigen::Matrix<double, 12, 5>;
bool distance_derivatives(bool edge, const PairVector12& y, const PairGeometry& g, PairVector12& grad, PairMatrix12& hess,
                          PairRange* range = nullptr) {
  const double d = g.diff.norm();
  if (!(d > 1e-12)) return false;
  double e[2][4] = {};
  int m = 0;
  if (edge) {
    const double s = g.weights[1], u = -g.weights[3];
    if (s > 0 && s < 1) e[m][0] = -1, e[m][1] = 1, ++m;
    if (u > 0 && u < 1) e[m][2] = 1, e[m][3] = -1, ++m;
  } else {
    int active[3], k = 0;
    for (int j = 0; j < 3; ++j)
      if (-g.weights[1 + j] > 0) active[k++] = j;
    for (int i = 1; i < k; ++i) e[m][1 + active[0]] = 1, e[m][1 + active[i]] = -1, ++m;
  }
  Eigen::Matrix<double, 3, 12> C;
  for (int j = 0; j < 4; ++j) C.block<3, 3>(0, 3 * j) = g.weights[j] * Mat3::Identity();
  grad = C.transpose() * g.diff / d;
  // Coefficient-based products (lazyProduct) throughout: at these sizes Eigen's general
  // product kernel costs more in its set-up than in its arithmetic.
  hess = C.transpose().lazyProduct(C);
  if (range) {
    range->setZero();
    range->leftCols<3>() = C.transpose() / std::sqrt(g.weights[0] * g.weights[0] + g.weights[1] * g.weights[1] +
                                                     g.weights[2] * g.weights[2] + g.weights[3] * g.weights[3]);
  }
  if (m > 0) {
    Eigen::Matrix<double, 3, 2> T = Eigen::Matrix<double, 3, 2>::Zero();
    Eigen::Matrix<double, 12, 2> G = Eigen::Matrix<double, 12, 2>::Zero();
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < 4; ++j) T.col(i) += e[i][j] * y.segment<3>(3 * j);
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < 4; ++j) G.block<3, 1>(3 * j, i) = e[i][j] * g.diff + g.weights[j] * T.col(i);
    // TᵀT over the m free parameters, the identity beyond (G's unused column is zero).
    Eigen::Matrix2d A = Eigen::Matrix2d::Identity();
    A.topLeftCorner(m, m) = T.leftCols(m).transpose() * T.leftCols(m);
    const double det = A.determinant(), scale = A(0, 0) * A(1, 1);
    if (!(scale > 0) || !(det > 1e-10 * scale)) return false;
    const Eigen::Matrix<double, 12, 2> GA = G * A.inverse();
    hess -= GA.lazyProduct(G.transpose());
    // G's columns orthogonalised against the basis so far (Gram–Schmidt, twice for rounding);
    // one in its span already stays zero.
    for (int i = 0; range && i < m; ++i) {
      PairVector12 q = G.col(i);
      const double length = q.norm();
      for (int pass = 0; pass < 2; ++pass)
        for (int k = 0; k < 3 + i; ++k) q -= range->col(k).dot(q) * range->col(k);
      if (q.norm() > 1e-10 * length) range->col(3 + i) = q.normalized();
    }
  }
  hess = (hess - grad * grad.transpose()) / d;
  return hess.allFinite();
}

// How far past the step the CCD follows a pair it clears: a step that uses no more than 0.375
// of every bound lets BDF2 double its next step (limit_scale in bdf2.cpp), so below that the
// ratio tells it nothing more. A cleared pair reported at 1 would hold BDF2's next step to
// three quarters of this one.
constexpr double kSmallestMeasuredRatio = 0.375;
// Pair Hessians to a chunk (core/parallel.hpp). A projected one costs about 1 µs, five distance
// queries; 400 to a chunk measures the same as 32 on the aortic and sample mitral closures
// (run-by-run ratios 1.01-1.02).
constexpr std::size_t kHessiansPerChunk = 32;

// Additive continuous collision detection (Li et al. 2021, "Codimensional Incremental
// Potential Contact", Algorithm 1) for one pair moving from y by t·p, t in [0, t_end]: how far
// along the step its gap s = d − ξ surely stays above `keep` · s(0). The motion relative to
// the pair's mean, p_j − p̄, bounds how fast any point of one side nears any point of the
// other: by l_p = |p_0 − p̄| + max_j |p_j − p̄| over the other side (a point of a triangle or
// an edge moves as a convex combination of its nodes). So from a gap s the pair may advance
// by 0.9 s / l_p and not touch; the distance is then measured again, and the advance stops
// before the first measured gap below keep · s(0) (between measurements the gap keeps a tenth
// of the last one measured). The gap is always measured at `checkpoint` on the way (t = 1: the
// step itself), so a pair followed past the step is cut no shorter than when followed to it.
// Unlike the supporting-plane bound it sees what the step does to the distance: a pair that
// slides or hinges past its neighbour at a tenth of a millimetre without nearing it is not cut
// to that tenth.
double additive_ccd_fraction(bool edge, const PairVector12& y, const PairVector12& p, double offset, double keep,
                             double t_end, double checkpoint) {
  Vec3 mean = Vec3::Zero();
  for (int j = 0; j < 4; ++j) mean += 0.25 * p.segment<3>(3 * j);
  double first = 0, second = 0;
  for (int j = 0; j < 4; ++j) {
    const double speed = (p.segment<3>(3 * j) - mean).norm();
    double& side = (edge ? j < 2 : j < 1) ? first : second;
    side = std::max(side, speed);
  }
  const double lp = first + second;
  if (!(lp > 0)) return t_end;
  auto gap_at = [&](double t) {
    const PairVector12 z = y + t * p;
    return pair_geometry(edge, z.segment<3>(0), z.segment<3>(3), z.segment<3>(6), z.segment<3>(9)).diff.norm() - offset;
  };
  const double s0 = gap_at(0), target = keep * s0;
  if (!(s0 > 0)) return 0;
  // The first advance may use the whole margin down to the target; later ones 0.9 of the
  // gap, as the distance is measured again after each (a pair that keeps a small gap while
  // sliding then takes ~l_p / gap advances; past kMaxAdvances the fraction reached stands).
  // A commissure's narrow pairs keep a few thousandths of a millimetre while their free sides
  // swing by a millimetre: ~300 advances clear such a step. With at most 200, those pairs cut
  // steps they never closed on, and the normal-valve study's 70 slack-root closures took 30,595
  // factorizations against 25,705 with 2,000 (the taut root's 100 the same either way; both
  // measured with BiCGStab's directions).
  constexpr int kMaxAdvances = 2000;
  double t = 0, advance = (s0 - target) / lp;
  for (int i = 0; i < kMaxAdvances && t < t_end; ++i) {
    const double next = std::min(t + advance, t < checkpoint ? std::min(checkpoint, t_end) : t_end);
    const double s = gap_at(next);
    if (!(s >= target)) return t;
    t = next;
    advance = 0.9 * s / lp;
  }
  return t;
}

// How much a pair's distance can change when its nodes move by `motion` (a step, or their
// displacement since some state): at most the largest relative motion of a node of one side
// and a node of the other, max |m_b − m_a| (each closest point moves by a convex combination
// of its side's node motions, so their difference by a convex combination of the m_b − m_a).
// Far tighter than each side's largest motion added up where a sheet moves as a whole:
// same-leaflet pairs within the detection distance, most of the candidates, keep their
// distance while the leaflet swings.
double relative_motion(const VecX& motion, const int (&nodes)[4], int first_side) {
  double m = 0;
  for (int a = 0; a < first_side; ++a)
    for (int b = first_side; b < 4; ++b) m = std::max(m, (node3(motion, nodes[b]) - node3(motion, nodes[a])).norm());
  return m;
}

}  // namespace

double PenaltyContactTerm::step_ratio(const VecX& x, const VecX& dx) const {
  // No state seen yet: the uniform bound, every node within max_step_length() = min(L, 0.4 δ).
  if (pair_gaps_.size() != face_pairs_.size() + edge_pairs_.size() || built_at_.size() != x.size())
    return ForceTerm::step_ratio(x, dx);
  // The candidate list: every node within 2L of where the list was built. Written as
  // (moved since the build + |dx|) / 2L rather than |dx| / (2L − moved), although both accept
  // the same steps: the first stays high while the list ages, which holds BDF2's step growth
  // back until the next rebuild. With the second (linear in the step) the remeshed Texas
  // TriValve closure grew its step into a chatter: 35,727 steps and 424 s against 2,103 steps
  // and 28 s (the sample mitral closure: 152 against 159 steps).
  double nodes_ratio = 0;
  for (int i = 0; i < dx.size() / 3; ++i)
    nodes_ratio =
        std::max(nodes_ratio, ((node3(x, i) - node3(built_at_, i)).norm() + dx.segment<3>(3 * i).norm()) / (2 * verlet_step()));
  // Every candidate pair closes by less than 0.8 max(δ, d); with the barrier, by less than
  // 0.8 (d − ξ), so that none reaches the offset (a narrow pair's own, scaled ξ).
  const double delta = opt_.separation;
  // A pair closes by at most twice the largest node step: one with room for that cannot raise
  // the ratio, and is not looked at further.
  const double largest_step = largest_node_norm(dx);
  // A pair's plane bound: how far it closes over 0.8 of its room. A pair recorded by a lower
  // bound of its gap that leaves room enough not to exceed `floor` has more, and is passed over
  // (plane 0); one that does not is measured where its gap was recorded (contacts_x_).
  struct Closing {
    size_t pair;
    double plane = 0, recorded_room = 0, room = 0;
    int nodes[4];  // pair_nodes(pair), for the collision search
    bool edge;
  };
  auto plane_bound = [&](size_t k, double floor) {
    Closing c{k};
    c.edge = pair_nodes(k, c.nodes);
    const int* nodes = c.nodes;
    const int first_side = c.edge ? 2 : 1;
    const double offset = pair_scale_[k] * opt_.offset;
    auto room_of = [&](const PairGap& g) {
      return barrier() ? std::max(g.distance - offset, 1e-300) : std::max(delta, g.distance);
    };
    const PairGap& recorded = pair_gaps_[k];
    c.recorded_room = room_of(recorded);
    if (2 * largest_step <= floor * 0.8 * c.recorded_room) return c;
    // The pair closes by at most its nodes' largest relative step; with the margin, a pair so
    // passed over could not have had a plane bound above `floor`.
    if (relative_motion(dx, c.nodes, first_side) * (1 + 1e-9) <= floor * 0.8 * c.recorded_room) return c;
    const PairGap g = recorded.lower_bound ? measured_gap(k, contacts_x_) : recorded;
    c.room = room_of(g);
    double closing = 0;
    for (int a = 0; a < first_side; ++a)
      for (int b = first_side; b < 4; ++b) {
        const Vec3 relative = node3(dx, nodes[b]) - node3(dx, nodes[a]);
        closing = std::max(closing, g.normal.isZero() ? relative.norm() : g.normal.dot(relative));
      }
    c.plane = closing / (0.8 * c.room);
    return c;
  };
  // Raises `ratio` to the pair's where it has too little room for the largest step (twice it:
  // both sides move) and its plane bound exceeds the ratio. With the barrier the pair is then
  // measured along the step and on past it (additive CCD, keeping the same 0.2 of its gap): its
  // ratio is the smaller of the two, the step's share of how far the pair may go.
  auto raise = [&](const Closing& c, double& ratio) {
    if (2 * largest_step <= ratio * 0.8 * c.recorded_room || 2 * largest_step <= ratio * 0.8 * c.room) return;
    if (c.plane <= ratio) return;
    double pair_ratio = c.plane;
    if (barrier()) {
      PairVector12 y, p;
      for (int j = 0; j < 4; ++j) y.segment<3>(3 * j) = node3(x, c.nodes[j]), p.segment<3>(3 * j) = node3(dx, c.nodes[j]);
      const double t_end = 1 / std::max(ratio, kSmallestMeasuredRatio);
      const double t = additive_ccd_fraction(c.edge, y, p, pair_scale_[c.pair] * opt_.offset, 0.2, t_end, 1.0);
      // A pair cleared to t_end rates 1 / t_end, written as what t_end is the inverse of:
      // 1 / (1 / r) need not round back to r, and the quasi-static solver cuts steps by r.
      pair_ratio = std::min(pair_ratio, t >= t_end ? std::max(ratio, kSmallestMeasuredRatio) : 1 / std::max(t, 1e-300));
    }
    ratio = std::max(ratio, pair_ratio);
  };
  // The pairs in order, each raising the ratio to its own: in order, because the collision
  // search stops where the pair could no longer raise the ratio, and where it stops decides
  // where it looks (searches with their own running ratios, chunk by chunk, look further, find
  // other fractions, and the sample mitral closure then took 171 factorizations, not 84).
  double ratio = nodes_ratio;
  const size_t n = face_pairs_.size() + edge_pairs_.size();
  const size_t chunks = chunks_for(n);
  if (chunks == 1 || worker_threads() == 1) {
    for (size_t k = 0; k < n; ++k) raise(plane_bound(k, ratio), ratio);
    return ratio;
  }
  // On more threads the plane bounds first, in chunks (core/parallel.hpp), each kept where it
  // exceeds the nodes' ratio (the least the ratio can be); then the same pass over those alone,
  // each check again at the ratio so far: the same ratio as the single pass, which passes a pair
  // over by the same checks. The floor is lower than that pass's running ratio, so more pairs are
  // measured: on one thread the single pass is the cheaper (BDF2's aortic closure 4.6 % more CPU).
  std::vector<std::vector<Closing>> kept_in(chunks);
  for_each_chunk(n, chunks, [&](size_t chunk, size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k)
      if (const Closing c = plane_bound(k, nodes_ratio); c.plane > nodes_ratio) kept_in[chunk].push_back(c);
  });
  std::vector<Closing> kept;
  append_chunks(kept, kept_in);
  for (const Closing& c : kept) raise(c, ratio);
  return ratio;
}

void PenaltyContactTerm::active_contacts(const VecX& x, std::vector<Contact>& out, std::vector<PairGap>* gaps) const {
  out.clear();
  const size_t n = face_pairs_.size() + edge_pairs_.size();
  if (gaps) gaps->assign(n, PairGap{});
  // The normal from the first side's point to the second's closest point (zero when they
  // coincide: no direction to bound the closing by).
  auto note_gap = [&](size_t k, double d, const Vec3& first_minus_second) {
    if (gaps) (*gaps)[k] = PairGap{d, d > 1e-12 ? Vec3(first_minus_second / d) : Vec3::Zero()};
  };
  const double delta = reach();
  // On the surface (d = 0) the direction is the face's normal, or the edges' common normal.
  auto add = [&](size_t k, bool edge, const int (&nodes)[4], std::vector<Contact>& found) {
    const Vec3 x0 = node3(x, nodes[0]), x1 = node3(x, nodes[1]), x2 = node3(x, nodes[2]), x3 = node3(x, nodes[3]);
    const PairGeometry g = pair_geometry(edge, x0, x1, x2, x3);
    const double d = g.diff.norm();
    note_gap(k, d, g.diff);
    if (d >= pair_scale_[k] * delta) return;
    Contact ct;
    ct.scale = pair_scale_[k];
    for (int j = 0; j < 4; ++j) ct.nodes[j] = nodes[j], ct.weights[j] = g.weights[j];
    ct.distance = d;
    ct.normal = d > 1e-12 ? Vec3(g.diff / d)
                          : Vec3(edge ? (x1 - x0).cross(x3 - x2).normalized() : (x2 - x1).cross(x3 - x1).normalized());
    ct.edge = edge;
    if (ct.normal.allFinite()) found.push_back(ct);
  };
  // With no gaps to record, a pair whose distance where update_couplings last measured every
  // gap, less twice the largest node move since, is still beyond the reach is skipped: each
  // point of either primitive moved by at most that much, so their distance by at most twice;
  // failing that, less its own nodes' relative motion since (relative_motion).
  // (On the aortic valve 1,100 of 45,000 candidates are active.)
  const bool bounded = !gaps && contacts_x_.size() == x.size() && pair_gaps_.size() == n;
  const bool since_build = gaps && built_at_.size() == x.size() && built_distance_.size() == n;
  // The nodes' displacement since the state the recorded gaps (bounded) or the build's
  // distances (since_build) hold for, once for every pair.
  VecX motion;
  if (bounded) motion = x - contacts_x_;
  if (since_build) motion = x - built_at_;
  const double moved = bounded ? largest_node_norm(motion) : 0.0;
  const double tolerance = 1e-9 * (1 + delta);
  const double beyond = delta + 2 * moved + tolerance;
  // Recording the gaps, a pair is measured only if it may be within reach: its distance when
  // the candidate list was built less its nodes' relative motion since bounds its distance now
  // from below. The rest keep that bound as their gap, and the step bound measures those it
  // cannot rule out with it (on the sample mitral closure 97 % of the gaps recorded are bounds,
  // and a quarter as many gaps are measured later by the step bound: a quarter of the distance
  // queries, the same iterates).
  // True when pair k is surely beyond the reach (its gap then recorded as that bound); side a
  // is the first `first_side` of the four nodes.
  auto out_of_reach = [&](size_t k, const int (&nodes)[4], int first_side) {
    if (bounded) return pair_gaps_[k].distance - relative_motion(motion, nodes, first_side) >= delta + tolerance;
    if (!since_build) return false;
    const double bound = built_distance_[k] - relative_motion(motion, nodes, first_side) - tolerance;
    if (bound < delta) return false;
    (*gaps)[k] = PairGap{bound, Vec3::Zero(), true};
    return true;
  };
  // Every pair on its own, in chunks (core/parallel.hpp); the contacts are gathered in order.
  const size_t chunks = chunks_for(n);
  std::vector<std::vector<Contact>> found(chunks);
  for_each_chunk(n, chunks, [&](size_t chunk, size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k) {
      if (bounded && pair_gaps_[k].distance >= beyond) continue;
      int nodes[4];
      const bool edge = pair_nodes(k, nodes);
      if (!out_of_reach(k, nodes, edge ? 2 : 1)) add(k, edge, nodes, found[chunk]);
    }
  });
  append_chunks(out, found);
}

bool PenaltyContactTerm::pair_nodes(size_t k, int (&nodes)[4]) const {
  if (k < face_pairs_.size()) {
    const auto& [i, t] = face_pairs_[k];
    const Tri& tri = topology_.triangles()[t];
    nodes[0] = i, nodes[1] = tri[0], nodes[2] = tri[1], nodes[3] = tri[2];
    return false;
  }
  const auto& [be, e] = edge_pairs_[k - face_pairs_.size()];
  const auto& edges = topology_.edges();
  nodes[0] = edges[be].first, nodes[1] = edges[be].second, nodes[2] = edges[e].first, nodes[3] = edges[e].second;
  return true;
}

PenaltyContactTerm::PairGap PenaltyContactTerm::measured_gap(size_t k, const VecX& x) const {
  int n[4];
  const bool edge = pair_nodes(k, n);
  const PairGeometry g = pair_geometry(edge, node3(x, n[0]), node3(x, n[1]), node3(x, n[2]), node3(x, n[3]));
  const double d = g.diff.norm();
  return PairGap{d, d > 1e-12 ? Vec3(g.diff / d) : Vec3::Zero()};
}

double PenaltyContactTerm::pair_energy(double d, double scale) const {
  const double k = opt_.stiffness, delta = scale * opt_.separation;
  if (!barrier()) return d < delta ? k * std::pow(delta - d, 3) / (3 * delta) : 0.0;
  const double s = d - scale * opt_.offset;
  if (s <= 0) return std::numeric_limits<double>::infinity();
  if (s >= delta) return 0.0;
  return -k * (s - delta) * (s - delta) * std::log(s / delta);
}

void PenaltyContactTerm::pair_force(double d, double scale, double& magnitude, double& slope) const {
  const double k = opt_.stiffness, delta = scale * opt_.separation;
  magnitude = slope = 0;
  if (!barrier()) {
    if (d >= delta) return;
    const double gap = delta - d;
    magnitude = k * gap * gap / delta, slope = 2 * k * gap / delta;
    return;
  }
  // Below s = 1e-9 ŝ the barrier is held at its value there: the step bound never lets a
  // pair come that close; this only keeps the numbers finite.
  const double s = std::max(d - scale * opt_.offset, 1e-9 * delta);
  if (s >= delta) return;
  const double u = s - delta, l = std::log(s / delta);
  magnitude = k * (2 * u * l + u * u / s);                    // −κ b'(s)
  slope = k * (-2 * l - 4 * u / s + u * u / (s * s));          // κ b''(s)
}

PenaltyContactTerm::PairVector PenaltyContactTerm::pair_gradient(bool edge, const PairVector& y, double scale) const {
  const PairGeometry g = pair_geometry(edge, y.segment<3>(0), y.segment<3>(3), y.segment<3>(6), y.segment<3>(9));
  const double d = g.diff.norm();
  PairVector gradient = PairVector::Zero();
  if (!(d > 1e-12)) return gradient;
  double magnitude = 0, slope = 0;
  pair_force(d, scale, magnitude, slope);
  for (int j = 0; j < 4; ++j) gradient.segment<3>(3 * j) = -magnitude * g.weights[j] * (g.diff / d);
  return gradient;
}

PenaltyContactTerm::PairMatrix PenaltyContactTerm::projected_pair_hessian(const Contact& c, const VecX& x) const {
  PairVector y;
  for (int j = 0; j < 4; ++j) y.segment<3>(3 * j) = node3(x, c.nodes[j]);
  PairMatrix H;
  PairVector grad;
  const bool exact = jacobian_mode_ == JacobianMode::exact;
  PairRange range;
  const PairGeometry g = pair_geometry(c.edge, y.segment<3>(0), y.segment<3>(3), y.segment<3>(6), y.segment<3>(9));
  const bool closed_form = distance_derivatives(c.edge, y, g, grad, H, exact ? nullptr : &range);
  if (closed_form) {
    double magnitude = 0, slope = 0;
    pair_force(g.diff.norm(), c.scale, magnitude, slope);
    H = slope * grad * grad.transpose() - magnitude * H;  // κ (b'' ∇d ∇dᵀ + b' ∇²d)
  } else {
    pair_hessian_by_differences(c.edge, y, c.scale, H);
  }
  const PairMatrix symmetric = 0.5 * (H + H.transpose());
  if (exact) return symmetric;
  if (!closed_form) {
    const Eigen::SelfAdjointEigenSolver<PairMatrix> eig(symmetric);
    return eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).asDiagonal() * eig.eigenvectors().transpose();
  }
  // H = Q S Qᵀ with Q = range: S's eigenpairs (λ, v) are H's (λ, Q v), and the rest of H's
  // eigenvalues are zero.
  const Eigen::Matrix<double, 5, 12> RH = range.transpose().lazyProduct(symmetric);
  const Eigen::Matrix<double, 5, 5> S = RH.lazyProduct(range);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 5, 5>> eig(0.5 * (S + S.transpose()));
  const PairRange W = range.lazyProduct(eig.eigenvectors());
  const PairRange WL = W * eig.eigenvalues().cwiseMax(0.0).asDiagonal();
  return WL.lazyProduct(W.transpose());
}

void PenaltyContactTerm::pair_hessian_by_differences(bool edge, const PairVector& y, double scale, PairMatrix& H) const {
  const double h = 1e-6;
  for (int k = 0; k < 12; ++k) {
    PairVector yp = y, ym = y;
    yp[k] += h;
    ym[k] -= h;
    H.col(k) = (pair_gradient(edge, yp, scale) - pair_gradient(edge, ym, scale)) / (2 * h);
  }
}

void PenaltyContactTerm::add(const State& s, VecX& f, BlockJacobian* dfdx, BlockJacobian*) const {
  std::vector<Contact> scratch;
  const std::vector<Contact>& contacts = contacts_at(s.x, scratch);
  stats_.active_pairs = static_cast<long>(contacts.size());
  stats_.closest_distance = -1;
  stats_.deepest_penetration = 0;
  // The barrier's pair Hessians (an eigendecomposition each where projected) in chunks
  // (core/parallel.hpp), added in order below.
  std::vector<PairMatrix> hessians;
  if (dfdx && barrier()) {
    hessians.resize(contacts.size());
    for_each_chunk(contacts.size(), chunks_for(contacts.size(), kHessiansPerChunk), [&](size_t, size_t begin, size_t end) {
      for (size_t k = begin; k < end; ++k) hessians[k] = projected_pair_hessian(contacts[k], s.x);
    });
  }
  for (size_t k = 0; k < contacts.size(); ++k) {
    const Contact& c = contacts[k];
    stats_.closest_distance = stats_.closest_distance < 0 ? c.distance : std::min(stats_.closest_distance, c.distance);
    stats_.deepest_penetration = std::max(stats_.deepest_penetration, c.scale * reach() - c.distance);
    double magnitude = 0, slope = 0;
    pair_force(c.distance, c.scale, magnitude, slope);
    for (int j = 0; j < 4; ++j) node3(f, c.nodes[j]) += magnitude * c.weights[j] * c.normal;
    if (!dfdx) continue;
    if (barrier()) {
      const PairMatrix& H = hessians[k];
      for (int j = 0; j < 4; ++j)
        for (int l = 0; l < 4; ++l) dfdx->add(c.nodes[j], c.nodes[l], Mat3(-H.block<3, 3>(3 * j, 3 * l)));
      continue;
    }
    const Mat3 nn = c.normal * c.normal.transpose();
    for (int j = 0; j < 4; ++j)
      for (int l = 0; l < 4; ++l)
        dfdx->add(c.nodes[j], c.nodes[l], (-slope * c.weights[j] * c.weights[l]) * nn);
  }
}

bool PenaltyContactTerm::energy(const State& s, double& e) const {
  std::vector<Contact> scratch;
  const std::vector<Contact>& contacts = contacts_at(s.x, scratch);
  double sum = 0;
  for (const Contact& c : contacts) sum += pair_energy(c.distance, c.scale);
  e += sum;
  return true;
}

}  // namespace valve
