// count_triangles MESH: prints the triangle count of a mesh read through the installed libvalve.
#include <cstdio>

#include "valve/io/mesh_io.hpp"

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  std::printf("%d\n", valve::read_mesh(argv[1]).num_triangles());
  return 0;
}
