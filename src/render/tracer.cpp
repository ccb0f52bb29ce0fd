#include "raylane/render/tracer.h"

#include "raylane/bvh/traverse_ref.h"
#include "raylane/prims/prim_list.h"
#include "raylane/trace/brute_force.h"

namespace raylane {

namespace {
constexpr std::string_view kNames[] = {"packet", "bvh", "scalar"};
}

std::optional<TracerKind> tracer_kind_from_name(std::string_view name) {
  for (int i = 0; i < 3; ++i)
    if (name == kNames[i]) return TracerKind(i);
  return std::nullopt;
}

std::string_view tracer_kind_name(TracerKind kind) {
  return kNames[int(kind)];
}

namespace {
constexpr std::string_view kPolicyNames[] = {"packets", "rays", "auto"};
}

std::optional<TraversalPolicy> traversal_policy_from_name(std::string_view name) {
  for (int i = 0; i < 3; ++i)
    if (name == kPolicyNames[i]) return TraversalPolicy(i);
  return std::nullopt;
}

std::string_view traversal_policy_name(TraversalPolicy policy) {
  return kPolicyNames[int(policy)];
}

void Tracer::closest(const std::vector<Rayd>& rays, std::vector<Hit>& hits, bool coherent) const {
  const std::ptrdiff_t n = std::ptrdiff_t(rays.size());
  hits.assign(rays.size(), Hit{});
  if (kind_ != TracerKind::kPacket) {
#pragma omp parallel for schedule(dynamic, 64)
    for (std::ptrdiff_t i = 0; i < n; ++i)
      hits[i] = kind_ == TracerKind::kBvh ? closest_hit_bvh_ref(scene_, bvh_, rays[i])
                                          : closest_hit_ref(scene_, rays[i]);
    return;
  }
  RayStream stream;
  stream.resize(rays.size());
  for (std::ptrdiff_t i = 0; i < n; ++i)
    stream.set(i, ray_cast<float>(rays[i]));
  HitStream out;
  bool single =
      policy_ == TraversalPolicy::kRays || (policy_ == TraversalPolicy::kAuto && !coherent);
  (single ? rays_ : packets_).closest(scene_, bvh_, stream, out);
#pragma omp parallel for schedule(dynamic, 64)
  for (std::ptrdiff_t i = 0; i < n; ++i) {
    if (out.prim[i] == PrimRef::kInvalidBits) continue;
    Hit& h = hits[i];
    Rayd traced = ray_cast<double>(stream.get(i));
    h.prim = PrimRef::from_bits(out.prim[i]);
    h.t = out.t[i];
    h.surface = dispatch(h.prim.tag(), [&](auto kind) {
      return surface_ref(scene_.table<decltype(kind)>(), h.prim.row(), traced, h.t);
    });
    h.front_face = dot(traced.d, h.surface.ng) < 0;
  }
}

}  // namespace raylane
