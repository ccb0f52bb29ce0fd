#include "tracers.h"

#include <cmath>
#include <map>
#include <mutex>

#include "embree_tracer.h"
#include "raylane/core/parallel.h"
#include "raylane/simd/isa.h"
#include "raylane/trace/bvh_ref.h"
#include "raylane/trace/simd_tracer.h"

namespace raylane::bench {

namespace {

// "raylane-<isa>": packets over the binary tree; "raylane-<isa>-rays": single rays over the
// 8-wide tree.
std::string packet_tracer_name(Isa isa, Traversal traversal) {
  return "raylane-" + std::string(isa_name(isa)) +
         (traversal == Traversal::kSingleRays ? "-rays" : "");
}

BenchTracer packet_tracer(const BenchScene& b, const Bvh& bvh, const std::string& name, Isa isa,
                          Traversal traversal) {
  SimdTracer t(isa, traversal);
  return {name,
          [&b, &bvh, t](const RayStream& rays, bool occlusion, HitStream& hits) {
            hits.resize(rays.size());
            parallel_chunks(rays.size(), kTraceChunk, [&](std::size_t begin, std::size_t end) {
              t.trace_range(b.scene, bvh, rays, begin, end, hits, occlusion);
            });
          },
          [&b, &bvh, t](const RayStream& rays, bool occlusion, HitStream& hits) {
            return t.trace_counted(b.scene, bvh, rays, hits, occlusion);
          }};
}

void trace_scalar(const BenchScene& b, const RayStream& rays, bool occlusion, HitStream& hits) {
  hits.resize(rays.size());
  const std::ptrdiff_t n = std::ptrdiff_t(rays.size());
#pragma omp parallel for schedule(dynamic, 256)
  for (std::ptrdiff_t i = 0; i < n; ++i) {
    Rayd r = ray_cast<double>(rays.get(std::size_t(i)));
    if (occlusion) {
      bool o = any_hit_bvh_ref(b.scene, b.bvh, r);
      hits.t[i] = 0, hits.prim[i] = o ? 0u : PrimRef::kInvalidBits;
    } else {
      Hit h = closest_hit_bvh_ref(b.scene, b.bvh, r);
      hits.t[i] = float(h.t), hits.prim[i] = h.prim.bits();
    }
  }
}

// The reference answers, cached per ray stream (they take as long as a scalar trace).
const HitStream& reference(const BenchScene& b, const RayStream& rays, bool occlusion,
                           std::size_t stride) {
  static std::mutex mutex;
  static std::map<std::pair<const RayStream*, std::size_t>, HitStream> cache;
  std::lock_guard<std::mutex> lock(mutex);
  auto key = std::make_pair(&rays, stride);
  if (auto it = cache.find(key); it != cache.end()) return it->second;
  RayStream sample;
  sample.resize((rays.size() + stride - 1) / stride);
  for (std::size_t i = 0, k = 0; i < rays.size(); i += stride, ++k)
    sample.set(k, rays.get(i));
  HitStream ref;
  trace_scalar(b, sample, occlusion, ref);
  return cache.emplace(key, std::move(ref)).first->second;
}

}  // namespace

std::vector<std::string> bench_tracer_names() {
  std::vector<std::string> names{kRenderTracerName};
  for (Traversal traversal : {Traversal::kPackets, Traversal::kSingleRays})
    for (Isa isa : supported_isas())
      names.push_back(packet_tracer_name(isa, traversal));
  names.push_back("raylane-scalar");
  if (embree_available()) {
    for (const char* mode : {"", "robust-"}) {
      names.push_back(std::string("embree-") + mode + "1");
      names.push_back(std::string("embree-") + mode + "16");
    }
  }
  return names;
}

BenchTracer bench_tracer(const BenchScene& b, const std::string& name) {
  // What `raylane render` runs: the widest ISA, packets (hybrid where its BVH has wide nodes).
  if (name == kRenderTracerName)
    return packet_tracer(b, b.rendered(), name, best_isa(), Traversal::kPackets);
  for (Traversal traversal : {Traversal::kPackets, Traversal::kSingleRays})
    for (Isa isa : supported_isas())
      if (name == packet_tracer_name(isa, traversal))
        return packet_tracer(b, b.bvh, name, isa, traversal);
  if (name == "raylane-scalar")
    return {name, [&b](const RayStream& r, bool o, HitStream& h) { trace_scalar(b, r, o, h); },
            nullptr};
  if (name.rfind("embree-", 0) == 0) {
    // "embree-[robust-]<width>"
    bool robust = name.rfind("embree-robust-", 0) == 0;
    std::string width_text = name.substr(robust ? 14 : 7);
    if (width_text != "1" && width_text != "16") return {name, nullptr, nullptr};
    int width = std::stoi(width_text);
    const EmbreeScene* e = embree_scene(b, robust ? EmbreeMode::kRobust : EmbreeMode::kDefault);
    return {name,
            [e, width](const RayStream& r, bool o, HitStream& h) { e->trace(r, o, width, h); },
            nullptr};
  }
  return {name, nullptr, nullptr};
}

Agreement check_against_reference(const BenchScene& b, const RayStream& rays, bool occlusion,
                                  const HitStream& hits, std::size_t stride) {
  const HitStream& ref = reference(b, rays, occlusion, stride);
  Agreement a;
  for (std::size_t i = 0, k = 0; i < rays.size(); i += stride, ++k) {
    ++a.checked;
    bool hit = hits.prim[i] != PrimRef::kInvalidBits,
         ref_hit = ref.prim[k] != PrimRef::kInvalidBits;
    bool same =
        hit == ref_hit && (occlusion || !hit || std::abs(hits.t[i] - ref.t[k]) <= 1e-4f * ref.t[k]);
    a.disagree += !same;
  }
  return a;
}

}  // namespace raylane::bench
