// Error bands for comparing the float packet kernels with the double references
// (docs/hard-cases.md §0): each ray is a clear hit, a clear miss, or lies in an ambiguous band,
// judged by the reference's signed margin (discriminant, slab overlap, edge function) against
// a bound on the float kernel's error in that margin. The bounds are derived from the
// operations the kernels in include/raylane/prims/ perform (see error_bands.cpp); a ray is
// never put in the band by a guessed tolerance.
//
// Used by the kernel tests (tests/simd/) and by bench/kernel_accuracy, which compiles this
// file too, so it depends on the library only (no GoogleTest).
#pragma once

#include <cstdint>
#include <limits>

#include "raylane/core/ray.h"
#include "raylane/prims/prim_list.h"
#include "raylane/scene/scene.h"
#include "support/interval.h"

namespace raylane::testing {

enum class RayClass { kClearHit, kClearMiss, kBand };
const char* ray_class_name(RayClass c);

// One yes/no decision of a kernel: the reference's signed margin (> 0 on the hit side) and a
// bound on how far the float kernel's value of it can be from the reference's. |margin| >
// bound decides the answer; otherwise the decision is in the band.
struct Criterion {
  double margin = 0;
  double bound = 0;
  RayClass verdict() const;
  // |margin| / bound: > 1 outside the band; how deep inside it a ray lies otherwise.
  double ratio() const;
};

// The verdict for one primitive: whether the float kernel certainly hits it, certainly misses
// it, or may do either, inside the ray's (tmin, tmax). `t` holds every t the kernel can
// commit for it (meaningful for kClearHit and, where finite, for kBand); `t_ref` is the
// reference's answer (+inf for a miss). `decisive` is the line criterion nearest its band.
struct PrimVerdict {
  RayClass cls = RayClass::kClearMiss;
  Interval t;
  double t_ref = std::numeric_limits<double>::infinity();
  Criterion decisive;
};

// Per kind: `ray` is the float ray converted exactly to double (docs/hard-cases.md §0), rows as
// stored.
PrimVerdict classify(const SphereTable& s, uint32_t row, const Rayd& ray);
PrimVerdict classify(const BoxTable& b, uint32_t row, const Rayd& ray);
PrimVerdict classify(const CylinderTable& c, uint32_t row, const Rayd& ray);
PrimVerdict classify(const TriangleTable& t, uint32_t row, const Rayd& ray);
PrimVerdict classify(const MovingSphereTable& s, uint32_t row, const Rayd& ray);
// CSG blocks: a clear miss when every leaf clearly misses the ray's range; anything else is
// left to the band (tests/prims/csg_packet_test.cpp judges blocks leaf by leaf).
PrimVerdict classify(const CsgTable& c, uint32_t row, const Rayd& ray);
// SDF blocks: the lanes march by the double reference (sdf_packet.h), so a reference miss is a
// clear miss; a hit is left to the band (tests/trace/sdf_packet_test.cpp holds the lanes to the
// reference's t rounded to float).
PrimVerdict classify(const SdfTable& s, uint32_t row, const Rayd& ray);
PrimVerdict classify(const Scene& scene, PrimRef prim, const Rayd& ray);

// The verdict for a closest-hit query on a whole scene. kClearHit: every primitive is a clear
// miss or a hit whose t interval lies clearly beyond the nearest clear hit, `prim`; the
// kernel's t is within `t_bound` of the reference's `t`. kClearMiss: every primitive is a
// clear miss (invalid rays too: the tracer must reject them). Otherwise kBand.
struct RayVerdict {
  RayClass cls = RayClass::kClearMiss;
  PrimRef prim = PrimRef::invalid();
  double t = std::numeric_limits<double>::infinity();
  double t_bound = 0;
  // kBand: |margin|/bound of the decision that made it ambiguous (a primitive's hit or miss,
  // or which of two hits is nearer).
  double band_ratio = 0;
};

// `skip_far_bounds`: primitives whose bounds, grown by 2^-12 of the distance scale, the ray's
// line misses are taken as clear misses without classifying them (for scenes of thousands of
// rows; see error_bands.cpp for why that is safe). The small-scene tests classify everything.
RayVerdict classify_closest(const Scene& scene, const Rayd& ray, bool skip_far_bounds = false);

}  // namespace raylane::testing
