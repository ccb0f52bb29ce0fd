// sobol_group (src/render/sobol.cpp) in lanes, one pixel per lane, instantiated per instruction
// set by src/render/shade_lanes_<isa>.cpp. Include from nowhere else. Every step is the scalar
// code's, on 32-bit unsigned lanes: the same values bit for bit (tests/render/sobol_test.cpp).
#pragma once

#include "raylane/render/sobol.h"
#include "raylane/simd/lanes.h"

namespace raylane::detail {

template <class A>
using U32 = simd::UInts<A>;

template <class A>
U32<A> reverse_bits_lanes(U32<A> x) {
  x = (x >> 16) | (x << 16);
  x = ((x & U32<A>(0xff00ff00u)) >> 8) | ((x & U32<A>(0x00ff00ffu)) << 8);
  x = ((x & U32<A>(0xf0f0f0f0u)) >> 4) | ((x & U32<A>(0x0f0f0f0fu)) << 4);
  x = ((x & U32<A>(0xccccccccu)) >> 2) | ((x & U32<A>(0x33333333u)) << 2);
  return ((x & U32<A>(0xaaaaaaaau)) >> 1) | ((x & U32<A>(0x55555555u)) << 1);
}

// Laine and Karras 2011 with Burley's constants, as scramble_reversed.
template <class A>
U32<A> scramble_reversed_lanes(U32<A> x, const U32<A>& seed) {
  x = x + seed;
  x = x ^ (x * U32<A>(0x6c50b47cu));
  x = x ^ (x * U32<A>(0xb82f1e52u));
  x = x ^ (x * U32<A>(0xc7afe638u));
  x = x ^ (x * U32<A>(0x8d22f6e6u));
  return x;
}

// Wellons's lowbias32, as hash32.
template <class A>
U32<A> hash32_lanes(U32<A> x) {
  x = x ^ (x >> 16);
  x = x * U32<A>(0x7feb352du);
  x = x ^ (x >> 15);
  x = x * U32<A>(0x846ca68bu);
  return x ^ (x >> 16);
}

template <class A>
void sobol_groups_range(uint32_t reversed_index, SobolBatch& b) {
  constexpr std::size_t W = simd::kWidth<A>;
  const uint32_t* tables = sobol_byte_tables();
  const U32<A> byte(0xffu);
  for (std::size_t i = 0; i < b.seed.size(); i += W) {
    U32<A> scramble = U32<A>::load_unaligned(b.scramble.data() + i);
    U32<A> seeds = U32<A>::load_unaligned(b.component.data() + i);
    U32<A> r = scramble_reversed_lanes<A>(U32<A>(reversed_index), scramble);
    U32<A> b0 = r & byte, b1 = ((r >> 8) & byte) + U32<A>(256u);
    U32<A> b2 = ((r >> 16) & byte) + U32<A>(512u), b3 = (r >> 24) + U32<A>(768u);
    for (uint32_t c = 0; c < 4; ++c) {
      const uint32_t* t = tables + 1024 * c;
      U32<A> point = simd::gather<A>(t, b0) ^ simd::gather<A>(t, b1) ^ simd::gather<A>(t, b2) ^
                     simd::gather<A>(t, b3);
      U32<A> v = scramble_reversed_lanes<A>(point, hash32_lanes<A>(seeds + U32<A>(c)));
      reverse_bits_lanes<A>(v).store_unaligned(b.u[c].data() + i);
    }
  }
}

}  // namespace raylane::detail
