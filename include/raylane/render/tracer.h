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

std::optional<TracerKind> tracer_kind_from_name(std::string_view name);  // packet, bvh, scalar
std::string_view tracer_kind_name(TracerKind kind);

class Tracer {
 public:
  Tracer(const Scene& scene, const Bvh& bvh, TracerKind kind, Isa isa = best_isa())
      : scene_(scene), bvh_(bvh), kind_(kind), packets_(isa) {}

  // The closest hit of every ray, with its surface (computed by the double reference from
  // the ray as traced). Packet rays are traced in float: origins and directions are rounded
  // first, and the surface is computed for the rounded ray, so t and the point agree.
  void closest(const std::vector<Rayd>& rays, std::vector<Hit>& hits) const;

  const Scene& scene() const { return scene_; }
  TracerKind kind() const { return kind_; }
  Isa isa() const { return packets_.isa(); }

 private:
  const Scene& scene_;
  const Bvh& bvh_;
  TracerKind kind_;
  PacketTracer packets_;
};

}  // namespace raylane
