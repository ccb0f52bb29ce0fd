// A ray o + t·d, valid for t in the open interval (tmin, tmax). Directions need not be
// normalised for the kernels, but the camera and the renderer produce unit directions. `time`
// is the instant in the shutter interval [0, 1) the ray is traced at; only moving primitives
// read it (motion blur, docs/motion-blur.md), and a ray nobody gave a time sees the middle of
// the shutter, as the ray-casting views render.
#pragma once

#include <limits>

#include "raylane/core/vec_math.h"

namespace raylane {

template <class T>
struct Ray {
  glm::vec<3, T> o{};
  glm::vec<3, T> d{};
  T tmin = T(0);
  T tmax = std::numeric_limits<T>::infinity();
  T time = T(0.5);

  constexpr glm::vec<3, T> at(T t) const { return o + d * t; }
};

using Rayf = Ray<float>;
using Rayd = Ray<double>;

template <class To, class From>
constexpr Ray<To> ray_cast(const Ray<From>& r) {
  return {glm::vec<3, To>(r.o), glm::vec<3, To>(r.d), To(r.tmin), To(r.tmax), To(r.time)};
}

}  // namespace raylane
