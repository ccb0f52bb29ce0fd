// Writes the benchmark's displaced icosphere at any size as a binary PLY triangle soup, for the
// scale runs of bench/README.md (import, build and render from 5k to 10M triangles):
//   make_icosphere --levels L OUT.ply      20·4^L triangles, the benchmark's own mesh at L = 8
//   make_icosphere --frequency K OUT.ply   20·K² triangles (K = 708: 10.0M)
#include <cstdio>
#include <cstdlib>
#include <string>

#include "icosphere.h"
#include "ply_export.h"

int main(int argc, char** argv) {
  if (argc != 4 || (std::string(argv[1]) != "--levels" && std::string(argv[1]) != "--frequency")) {
    std::fprintf(stderr, "usage: make_icosphere (--levels L | --frequency K) OUT.ply\n");
    return 2;
  }
  int n = std::atoi(argv[2]);
  if (n < 0 || n > 4000) {
    std::fprintf(stderr, "make_icosphere: %s out of range\n", argv[2]);
    return 2;
  }
  raylane::TriangleTable table;
  if (std::string(argv[1]) == "--levels")
    raylane::bench::add_displaced_icosphere(table, n, 0);
  else
    raylane::bench::add_displaced_geodesic_sphere(table, n, 0);
  raylane::Status done = raylane::bench::write_ply_soup(argv[3], table);
  if (!done) {
    std::fprintf(stderr, "%s\n", done.error().c_str());
    return 1;
  }
  std::printf("wrote %zu triangles to %s\n", std::size_t(table.size()), argv[3]);
  return 0;
}
