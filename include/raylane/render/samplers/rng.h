// Random numbers for the path tracer: MT19937-64 (the course's generator), one stream per
// (image seed, tile, pass), so an image does not depend on which thread renders which tile.
#pragma once

#include <cstdint>
#include <random>

namespace raylane {

// SplitMix64's finaliser (Steele, Lea and Flood 2014, "Fast splittable pseudorandom number
// generators"): a bijective mix whose output bits each depend on every input bit, so nearby
// (tile, pass) keys give unrelated seeds. Written once over the number type: U64 = uint64_t
// (mix64) or 64-bit unsigned lanes (the Sobol groups' seeds,
// src/render/samplers/sobol_lanes_impl.h), modulo 2^64 in both.
template <class U64>
constexpr U64 splitmix64_finaliser(U64 z) {
  z = z + U64(0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * U64(0xbf58476d1ce4e5b9ull);
  z = (z ^ (z >> 27)) * U64(0x94d049bb133111ebull);
  return z ^ (z >> 31);
}
constexpr uint64_t mix64(uint64_t z) {
  return splitmix64_finaliser(z);
}

class Rng {
 public:
  explicit Rng(uint64_t seed) : engine_(seed) {}
  static Rng for_tile(uint64_t image_seed, uint64_t tile, uint64_t pass) {
    return Rng(mix64(mix64(mix64(image_seed) ^ tile) ^ (pass * 0x632be59bd9b4e019ull)));
  }
  // Uniform in [0, 1): the top 53 bits as a double's mantissa, so 1 is never returned.
  double uniform() { return double(engine_() >> 11) * 0x1p-53; }

 private:
  std::mt19937_64 engine_;
};

}  // namespace raylane
