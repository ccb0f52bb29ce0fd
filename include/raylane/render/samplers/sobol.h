// Owen-scrambled Sobol points for the path tracer (Burley 2020, "Practical Hash-based Owen
// Scrambling", JCGT 9(4)): the first four Sobol dimensions, each scrambled by a hash that acts
// as a nested uniform (Owen) scramble, and the point index itself shuffled the same way per
// group of four dimensions ("padding"), so that groups — a path's decisions at different
// bounces — are independent while each group keeps the Sobol net's stratification. Every value
// is a function of (seed, index, group, component): no state, so a pixel's samples do not
// depend on the thread or the order they are drawn in.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "raylane/simd/isa.h"

namespace raylane {

// A number u in [0, 1) as float: rounded to nearest, but never up to 1 (every u above
// 1 − 2^-25 would round to 1). The float shading picks a lobe by u < pd, and pd is 1 for a
// material that is diffuse alone, so a 1 would pick a lobe it does not have.
// (std::min's comparison, written out, and a template on a tag that the per-ISA units set to
// their instruction set: see sobol_unit in render/samplers/sobol_steps.h.)
inline constexpr float kLargestBelowOne = 0x1.fffffep-1f;
template <class Tag = void>
float unit_float(double u) {
  const float f = float(u);
  return kLargestBelowOne < f ? kLargestBelowOne : f;
}

// The 32-bit Sobol point of `index` in dimension d = 0..3 (dimension 0 is van der Corput's
// radical inverse; 1..3 use Joe and Kuo's 2008 direction numbers, "Constructing Sobol
// sequences with better two-dimensional projections", SIAM J. Sci. Comput. 30(5)).
uint32_t sobol_point(uint32_t index, int d);

// A nested uniform scramble of x's bits by `seed`: bit k is flipped by a hash of the bits above
// it, so every dyadic interval maps to another of the same size (what keeps a net a net).
uint32_t owen_scramble(uint32_t x, uint32_t seed);

// Point `index` of the scrambled 4-D Sobol group `group` for the pixel whose seed is `seed`,
// each component in [0, 1) with 32-bit resolution. Components 0 and 1 together form a
// (0, 2)-sequence: the first 2^m points stratify every dyadic rectangle of area 2^-m.
std::array<double, 4> sobol_group(uint64_t seed, uint32_t index, uint32_t group);

// sobol_group for many pixels at once, in SIMD lanes: after sobol_groups(), row i's component
// c is u[c][i]·2^-32, bit for bit sobol_group(seed[i], index, group)[c].
struct SobolBatch {
  std::vector<uint64_t> seed;                 // rows [0, size): the pixels' seeds
  std::array<std::vector<uint32_t>, 4> u;     // the 32-bit components
  std::vector<uint32_t> scramble, component;  // per row: the index's and components' seeds
  std::size_t size() const { return size_; }
  // Rows [0, rows) and their padding to 16 lanes, whose seeds are whatever they were (their
  // groups are computed and unread). The columns never shrink.
  void resize(std::size_t rows);
  std::size_t padded_size() const { return (size_ + 15) / 16 * 16; }

 private:
  std::size_t size_ = 0;
};
// Where sobol_groups also writes component c of rows [0, size) as the number it stands for,
// u[c]·2^-32 (sobol_group's, bit for bit): into a double column, a float column (unit_float:
// rounded to nearest, and below 1), both or neither (null). The consumers' own columns,
// written in the same call instead of a pass of their own.
struct SobolNumbers {
  std::array<double*, 4> as_double{};
  std::array<float*, 4> as_float{};
};
// Only the components in the set `components` (bit c: component c) are computed, 0 and 1
// always; the others keep what they held. A decision that reads fewer numbers saves the rest,
// dimensions 2 and 3 most (table gathers).
inline constexpr unsigned kAllComponents = 0xfu;
// What a group adds to a pixel's seed before the group's hash: seed ^ group_salt(group). Group
// 0's salt is 0, so sobol_groups for group 0 on seeds already salted by group_salt(g) gives
// group g's numbers: a batch whose rows are at different depths (a wavefront that refills)
// draws each row's own group in one call.
constexpr uint64_t group_salt(uint32_t group) {
  return uint64_t(group) * 0x9e3779b97f4a7c15ull;
}
constexpr unsigned first_components(int n) {
  return (1u << n) - 1u;
}
void sobol_groups(Isa isa, uint32_t index, uint32_t group, SobolBatch& batch,
                  unsigned components = kAllComponents, const SobolNumbers& numbers = {});

namespace detail {
// The byte tables of dimensions 2 and 3, [dimension − 2][byte][value], in the bit-reversed
// domain (sobol.cpp): what render/samplers/sobol_steps.h's reversed_table_point looks up.
const uint32_t* sobol_byte_tables();
// The same product by chunks of `bits` = 3 or 4 bits, [dimension − 2][chunk][value], each
// chunk's 8 or 16 words 64-byte aligned: what the lanes read by register permutes.
const uint32_t* sobol_chunk_tables(int bits);
}  // namespace detail

}  // namespace raylane
