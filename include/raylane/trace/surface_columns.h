// Hit surfaces written as columns rather than into Hit records: the path tracer's lane rows take
// their surfaces this way (Tracer::surfaces), straight into the batches its lanes read, so
// that no 96-byte Hit is written for a vertex only to be read back field by field.
#pragma once

#include <cstdint>

namespace raylane {

// Row r of a request gets the surface of its r-th hit. Every pointer addresses at least as
// many rows as the request has.
struct SurfaceColumns {
  // The hit point and the unit geometric normal in float: from the kind's float lanes where it
  // has them (surface_float_lanes), else its double surface rounded to nearest.
  float *px, *py, *pz;
  float *ngx, *ngy, *ngz;
  float *nsx, *nsy, *nsz;  // the unit shading normal in float (a float BSDF's frame)
  // A bound on the float point's error whose projection on the normal bounds its distance from
  // the true surface (what offset_origin clears): the kind's own where its float lanes give one
  // (sphere_point_bound, box_point_bound, triangle_point_bound, cylinder_point_bound), else
  // float_hit_point_bound (core/ray_offset.h), componentwise, which counts the rounding.
  float *ex, *ey, *ez;
  double* cos_ns;  // dot(ns, d): the Bsdf's black() test
  uint8_t* front;  // 1 where the ray meets the front face (dot(d, ng) < 0), else 0
};

}  // namespace raylane
