// What a packet traversal did: the figures that explain its speed (nodes and primitives
// tested per ray, how many lanes of each SIMD test did useful work). Counted only by the
// counting instantiation of the traversal (SimdTracer::trace_counted); the production
// loop carries no counters.
#pragma once

#include <cstdint>

namespace raylane {

struct TraversalCounters {
  int width = 0;               // lanes per packet
  uint64_t rays = 0;           // rays traced
  uint64_t packets = 0;        // packets traced
  uint64_t node_tests = 0;     // packet × node box tests
  uint64_t lanes_active = 0;   // Σ over node tests: lanes still being traced
  uint64_t lanes_overlap = 0;  // Σ over node tests: lanes whose segment overlapped the box
  uint64_t leaf_visits = 0;    // packet × leaf visits
  uint64_t prim_tests = 0;     // packet × primitive tests (each one W lanes wide)
  // Lanes a packet handed to single-ray traversal (trace/packet_traverse.h), and the wide
  // nodes and rows those single rays tested.
  uint64_t single_rays = 0, single_node_tests = 0, single_prim_tests = 0;

  void add(const TraversalCounters& o) {
    width = o.width ? o.width : width;
    rays += o.rays, packets += o.packets, node_tests += o.node_tests;
    lanes_active += o.lanes_active, lanes_overlap += o.lanes_overlap;
    leaf_visits += o.leaf_visits, prim_tests += o.prim_tests;
    single_rays += o.single_rays, single_node_tests += o.single_node_tests;
    single_prim_tests += o.single_prim_tests;
  }
  double per_ray(uint64_t v) const { return rays ? double(v) / double(rays) : 0.0; }
  // Share of the lanes of node tests that overlapped the box: SIMD utilisation.
  double lane_utilisation() const {
    return node_tests ? double(lanes_overlap) / (double(node_tests) * width) : 0.0;
  }
};

}  // namespace raylane
