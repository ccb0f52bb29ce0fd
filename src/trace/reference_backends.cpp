// The two reference backends (trace/trace_backend.h): every ray traced on its own in double,
// through the BVH or against every primitive. They differ in two functions, closest_one and
// any_one; the batch loops, aimed shadow rays and surfaces are written once, in Reference.
#include <cassert>

#include "raylane/trace/brute_force.h"
#include "raylane/trace/bvh_ref.h"
#include "raylane/trace/trace_backend.h"

namespace raylane {

namespace {

class Reference : public TraceBackend {
 public:
  void closest(const std::vector<Rayd>& rays, std::vector<Hit>& hits,
               TraceScratch&) const override {
    hits.resize(rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i)
      hits[i] = closest_one(rays[i]);
  }
  void occluded(const std::vector<Rayd>& rays, const std::vector<PrimRef>& aims,
                std::vector<uint8_t>& blocked, TraceScratch&) const override {
    assert(aims.empty() || aims.size() == rays.size());  // the contract in tracer.h
    blocked.resize(rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i)
      blocked[i] = occluded_one(rays[i], aims.empty() ? PrimRef::invalid() : aims[i]);
  }
  void closest(const RayStream& rays, std::vector<Hit>& hits, std::size_t,
               TraceScratch&) const override {
    hits.resize(rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i)
      hits[i] = closest_one(ray_cast<double>(rays.get(i)));
  }
  void occluded(const RayStream& rays, std::vector<uint8_t>& blocked,
                TraceScratch&) const override {
    const bool aimed = !rays.aim.empty();
    blocked.resize(rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i)
      blocked[i] = occluded_one(ray_cast<double>(rays.get(i)),
                                aimed ? PrimRef::from_bits(rays.aim[i]) : PrimRef::invalid());
  }
  void closest(const RayStream& rays, HitStream& hits, TraceScratch&) const override {
    hits.resize(rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i) {
      const Hit h = closest_one(ray_cast<double>(rays.get(i)));
      hits.t[i] = float(h.t);  // +inf for a miss
      hits.prim[i] = h.prim.bits();
    }
  }
  void surfaces(const RayStream& rays, const HitStream& hits, std::span<const uint32_t> ray,
                const SurfaceColumns& out, TraceScratch&) const override {
    for (std::size_t r = 0; r < ray.size(); ++r) {
      const PrimRef prim = PrimRef::from_bits(hits.prim[ray[r]]);
      const Rayd traced = ray_cast<double>(rays.get(ray[r]));
      const double t = hits.t[ray[r]];
      store_surface(out, r, scene(), prim, surface_of(scene(), prim, traced, t), traced, t);
    }
  }

 protected:
  virtual const Scene& scene() const = 0;
  virtual Hit closest_one(const Rayd& ray) const = 0;
  virtual bool any_one(const Rayd& ray) const = 0;

 private:
  // A ray aimed at `aim` is blocked when its closest hit is something else.
  bool occluded_one(const Rayd& ray, PrimRef aim) const {
    if (!aim.valid()) return any_one(ray);
    const Hit h = closest_one(ray);
    return h.hit() && h.prim != aim;
  }
};

class BvhReference final : public Reference {
 public:
  BvhReference(const Scene& scene, const Bvh& bvh) : scene_(scene), bvh_(bvh) {}

 private:
  const Scene& scene() const override { return scene_; }
  Hit closest_one(const Rayd& ray) const override { return closest_hit_bvh_ref(scene_, bvh_, ray); }
  bool any_one(const Rayd& ray) const override { return any_hit_bvh_ref(scene_, bvh_, ray); }
  const Scene& scene_;
  const Bvh& bvh_;
};

class BruteForce final : public Reference {
 public:
  explicit BruteForce(const Scene& scene) : scene_(scene) {}

 private:
  const Scene& scene() const override { return scene_; }
  Hit closest_one(const Rayd& ray) const override { return closest_hit_ref(scene_, ray); }
  bool any_one(const Rayd& ray) const override { return any_hit_ref(scene_, ray); }
  const Scene& scene_;
};

}  // namespace

std::unique_ptr<const TraceBackend> bvh_reference_backend(const Scene& scene, const Bvh& bvh) {
  return std::make_unique<BvhReference>(scene, bvh);
}

std::unique_ptr<const TraceBackend> brute_force_backend(const Scene& scene) {
  return std::make_unique<BruteForce>(scene);
}

}  // namespace raylane
