#include "raylane/trace/brute_force.h"

#include <cmath>

#include "raylane/prims/prim_list.h"

namespace raylane {

bool ray_is_valid(const Rayd& r) {
  return is_finite(r.o) && is_finite(r.d) && !std::isnan(r.tmin) && !std::isnan(r.tmax) &&
         r.tmin <= r.tmax && length_squared(r.d) > 0;
}

Hit closest_hit_ref(const Scene& scene, const Rayd& ray) {
  Hit best;
  if (!ray_is_valid(ray)) return best;
  PrimKinds::for_each([&](auto kind) {
    using Kind = decltype(kind);
    const auto& table = scene.table<Kind>();
    for (uint32_t row = 0; row < table.size(); ++row) {
      auto [t, hit_row] = hit_ref<Kind>(table, row, ray);
      PrimRef ref(tag_of<Kind>, hit_row);
      if (t < best.t || (t == best.t && t < ray.tmax && ref < best.prim)) {
        best.t = t;
        best.prim = ref;
      }
    }
  });
  if (best.hit()) {
    best.surface = dispatch(best.prim.tag(), [&](auto kind) {
      return surface_ref(scene.table<decltype(kind)>(), best.prim.row(), ray, best.t);
    });
    best.front_face = dot(ray.d, best.surface.ng) < 0;
  }
  return best;
}

bool any_hit_ref(const Scene& scene, const Rayd& ray) {
  if (!ray_is_valid(ray)) return false;
  bool found = false;
  PrimKinds::for_each([&](auto kind) {
    const auto& table = scene.table<decltype(kind)>();
    for (uint32_t row = 0; row < table.size() && !found; ++row)
      found = intersect_ref(table, row, ray) < ray.tmax;
  });
  return found;
}

}  // namespace raylane
