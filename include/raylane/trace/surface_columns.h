// Hit surfaces written as columns rather than into Hit records: the path tracer's lane rows take
// their surfaces this way (Tracer::surfaces), straight into the batches its lanes read, so
// that no 96-byte Hit is written for a vertex only to be read back field by field.
#pragma once

#include <cstdint>

namespace raylane {

// Row r of a request gets the surface of its r-th hit. Every pointer addresses at least as
// many rows as the request has.
struct SurfaceColumns {
  // The hit point and the unit geometric normal, rounded to nearest float: the render's float
  // vertex steps bound the point's error with that rounding counted (float_hit_point_bound,
  // core/ray_offset.h).
  float *px, *py, *pz;
  float *ngx, *ngy, *ngz;
  float *nsx, *nsy, *nsz;  // the unit shading normal, rounded to float (a float BSDF's frame)
  double* cos_ns;          // dot(ns, d) in double, before the rounding: the Bsdf's black() test
  uint8_t* front;          // 1 where the ray meets the front face (dot(d, ng) < 0), else 0
};

}  // namespace raylane
