// The tracers a renderer can use, behind one batch interface: the packet tracer (default),
// single rays through the BVH with the double kernels, or the brute-force oracle. All three
// see the same scene (its tables permuted by the BVH build), so their answers — including
// primitive ids — can be compared pixel for pixel.
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include "raylane/bvh/bvh.h"
#include "raylane/scene/scene.h"
#include "raylane/trace/hit.h"
#include "raylane/trace/packet_tracer.h"

namespace raylane {

enum class TracerKind { kPacket, kBvh, kScalar };

// How the packet tracer takes a batch: always packets, always single rays, or packets for
// coherent batches (camera rays) and single rays for the rest (bounces, shadow rays).
enum class TraversalPolicy { kPackets, kRays, kAuto };
std::optional<TraversalPolicy> traversal_policy_from_name(
    std::string_view name);  // packets, rays, auto
std::string_view traversal_policy_name(TraversalPolicy policy);

std::optional<TracerKind> tracer_kind_from_name(std::string_view name);  // packet, bvh, scalar
std::string_view tracer_kind_name(TracerKind kind);

class Tracer {
 public:
  // Single rays (policy kRays or kAuto) need `bvh` built with BvhConfig::wide_nodes.
  Tracer(const Scene& scene, const Bvh& bvh, TracerKind kind, Isa isa = best_isa(),
         TraversalPolicy policy = TraversalPolicy::kPackets)
      : scene_(scene),
        bvh_(bvh),
        kind_(kind),
        policy_(policy),
        packets_(isa, Traversal::kPackets),
        rays_(isa, Traversal::kSingleRays) {}

  // The closest hit of every ray, with its surface (computed by the double reference from
  // the ray as traced). Packet rays are traced in float: origins and directions are rounded
  // first, and the surface is computed for the rounded ray, so t and the point agree.
  // `coherent`: the batch is camera rays in tiles (packets pay) rather than bounces.
  void closest(const std::vector<Rayd>& rays, std::vector<Hit>& hits, bool coherent = true) const;

  const Scene& scene() const { return scene_; }
  TracerKind kind() const { return kind_; }
  Isa isa() const { return packets_.isa(); }

 private:
  const Scene& scene_;
  const Bvh& bvh_;
  TracerKind kind_;
  TraversalPolicy policy_;
  PacketTracer packets_, rays_;
};

}  // namespace raylane
