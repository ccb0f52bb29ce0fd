// Rays and answers as plain structure-of-arrays streams: what crosses from baseline code into
// the per-ISA packet tracers (only pointers and scalars cross that boundary, docs/design.md, "SIMD
// and the instruction sets"). The tracer takes W consecutive rays as one packet, so camera rays
// stored in small tiles make coherent packets.
#pragma once

#include <cstdint>
#include <vector>

#include "raylane/core/column.h"
#include "raylane/core/prim_ref.h"
#include "raylane/core/ray.h"

namespace raylane {

struct RayStream {
  // Columns (core/column.h): resize() leaves new rows for the caller to write.
  Column<float> ox, oy, oz, dx, dy, dz, tmin, tmax;
  // Occlusion only, optional (empty, or one entry per ray): aim[i] is the PrimRef bits of the
  // primitive ray i is aimed at, a light for a shadow ray (PrimRef::kInvalidBits: none). Its
  // surface ends the ray's segment instead of blocking it (SimdTracer::occluded). resize() and
  // set() leave it alone.
  Column<uint32_t> aim;
  // Motion blur only, optional (empty, or one entry per ray): time[i] is ray i's instant in the
  // shutter interval [0, 1). A scene without moving primitives never fills it (its rays are
  // traced as they always were); an empty column means the middle of the shutter, as for a
  // Ray without a time. resize() leaves it alone; set() writes it when it is there.
  Column<float> time;

  std::size_t size() const { return ox.size(); }
  void resize(std::size_t n) {
    for (auto* c : {&ox, &oy, &oz, &dx, &dy, &dz, &tmin, &tmax})
      c->resize(n);
  }
  void set(std::size_t i, const Rayf& r) {
    ox[i] = r.o.x, oy[i] = r.o.y, oz[i] = r.o.z;
    dx[i] = r.d.x, dy[i] = r.d.y, dz[i] = r.d.z;
    tmin[i] = r.tmin, tmax[i] = r.tmax;
    if (i < time.size()) time[i] = r.time;
  }
  // The stream of `rays`, each rounded to float (what the packet tracer is given), with a time
  // column when a ray's time is not the middle of the shutter.
  static RayStream from(const std::vector<Rayd>& rays) {
    RayStream s;
    s.resize(rays.size());
    for (const Rayd& r : rays)
      if (r.time != 0.5) {
        s.time.resize(rays.size());
        break;
      }
    for (std::size_t i = 0; i < rays.size(); ++i)
      s.set(i, ray_cast<float>(rays[i]));
    return s;
  }
  Rayf get(std::size_t i) const {
    return {{ox[i], oy[i], oz[i]}, {dx[i], dy[i], dz[i]}, tmin[i], tmax[i], time_of(i)};
  }
  float time_of(std::size_t i) const { return time.empty() ? 0.5f : time[i]; }
  // No rays, no aims, no times (the columns keep their capacity).
  void clear() {
    resize(0);
    aim.clear();
    time.clear();
  }
};

// Appends rays to a stream without a capacity check per column and ray: room for `most` more
// is made once, and what was not used is trimmed when the appender goes. With `aimed`, the aim
// column grows with the rays (push(ray, aim)); without, it is left alone.
class RayAppender {
 public:
  RayAppender(RayStream& s, std::size_t most, bool aimed) : s_(s), next_(s.size()), aimed_(aimed) {
    s_.resize(next_ + most);
    if (aimed_) s_.aim.resize(next_ + most);
  }
  ~RayAppender() {
    s_.resize(next_);
    if (aimed_) s_.aim.resize(next_);
  }
  RayAppender(const RayAppender&) = delete;
  RayAppender& operator=(const RayAppender&) = delete;

  void push(const Rayf& r) { s_.set(next_++, r); }
  void push(const Rayf& r, uint32_t aim) {
    s_.aim[next_] = aim;
    push(r);
  }

 private:
  RayStream& s_;
  std::size_t next_;
  bool aimed_;
};

struct HitStream {
  Column<float> t;        // +inf for a miss
  Column<uint32_t> prim;  // PrimRef bits; PrimRef::kInvalidBits for a miss

  void resize(std::size_t n) {
    t.resize(n);
    prim.resize(n);
  }
};

}  // namespace raylane
