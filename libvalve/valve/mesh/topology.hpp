#pragma once
// Edges, edge-to-triangle adjacency and boundary loops of a triangle mesh.
#include <array>
#include <vector>

#include "valve/mesh/tri_mesh.hpp"

namespace valve {

struct Edge {
  int a, b;                     // a < b
  std::array<int, 2> tris;      // adjacent triangles; tris[1] = -1 on the boundary
};

struct Topology {
  std::vector<Edge> edges;
  std::vector<std::vector<int>> loops;  // boundary loops as ordered node lists
  int non_manifold_edges = 0;           // edges shared by more than two triangles
};

/// Builds edges (sorted by (a, b)) and boundary loops.
Topology build_topology(const std::vector<Tri>& triangles, int num_nodes);

/// Whether two triangles share a node.
bool share_vertex(const Tri& a, const Tri& b);

/// Unique undirected node pairs (a < b) of all triangle edges.
std::vector<std::pair<int, int>> unique_edges(const std::vector<Tri>& triangles);

}  // namespace valve
