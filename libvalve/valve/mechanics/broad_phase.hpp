#pragma once
// Broad phase of contact detection (seed 4.2.3): which (node, triangle) pairs are close
// enough to be worth an exact test. Each triangle's axis-aligned bounding box is inflated
// by a margin; a pair is a candidate when the node lies inside the inflated box.
//
// Three interchangeable methods give the same pairs (tests/mechanics check this):
//  - sweep_and_prune: the seed's sorted list of boxes. Boxes are sorted by their lower x
//    bound and swept against the nodes sorted by x, keeping the boxes that straddle the
//    sweep line active. O((N + T) log T + active set); degrades when many boxes share an
//    x range (a valve seen along its axis).
//  - spatial_hash: a uniform grid whose cell is the mean inflated box size; each box is
//    listed in the cells it overlaps, each node looks up its own cell. O(N + T) expected,
//    insensitive to orientation.
//  - bvh: a bounding volume hierarchy over the boxes (median splits along the longest axis,
//    leaves of four), each node walking the subtrees whose box holds it. O(T log T) to build,
//    O(log T + pairs) per node, insensitive to orientation and to boxes of mixed sizes.
// `valve-bench --broad-phase` measures all three (docs/results/performance.md).
#include <string>
#include <utility>
#include <vector>

#include "valve/core/types.hpp"

namespace valve {

enum class BroadPhaseMethod { sweep_and_prune, spatial_hash, bvh };

BroadPhaseMethod parse_broad_phase(const std::string& name);  // throws InputError
std::string to_string(BroadPhaseMethod m);

/// Candidate (node, triangle) pairs, sorted by node then triangle. `x` holds 3N positions;
/// only nodes with `query[i]` true are tested (all when `query` is empty).
std::vector<std::pair<int, int>> broad_phase_pairs(const VecX& x, const std::vector<Tri>& triangles,
                                                   double margin, BroadPhaseMethod method,
                                                   const std::vector<char>& query = {});

/// Candidate (query edge, edge) pairs, sorted: the edges whose axis-aligned boxes come
/// within `margin` of a query edge's box on every axis (so every pair of segments closer
/// than `margin` is among them), the query edge itself excluded; a pair of two query edges
/// appears once, as (lower, higher). The same uniform grid as spatial_hash, over the edge
/// boxes, each query visiting the cells its inflated box overlaps. Why a grid rather than a
/// sweep over the edges sorted by lower x bound: the sweep prunes poorly when every edge is a
/// query (contact.interior_edges). On the mitral x16 closure the candidate lists take 18.6 s
/// with the grid (and each pair of query edges once) against 31.4 s with the sweep, identical
/// pairs; most of the 18.6 s is the exact distances of its 4.9 million pairs.
std::vector<std::pair<int, int>> edge_box_pairs(const VecX& x, const std::vector<std::pair<int, int>>& edges,
                                                const std::vector<int>& query_edges, double margin);

}  // namespace valve
