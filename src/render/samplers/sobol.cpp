#include "raylane/render/samplers/sobol.h"

#include <array>
#include <bit>

#include "raylane/render/samplers/rng.h"
#include "raylane/render/samplers/sobol_steps.h"
#include "render/render_lanes.h"

namespace raylane {

namespace {

using Matrix = std::array<uint32_t, 32>;  // column k: the bits index bit k contributes

// Sobol's recurrence for one dimension (Bratley and Fox 1988, "Algorithm 659"): a primitive
// polynomial of degree s with inner coefficients a (bit s−2 is the coefficient of x^(s−1)),
// initial odd integers m_1..m_s, then m_k = 2a_1·m_(k−1) ⊕ 2²a_2·m_(k−2) ⊕ … ⊕ 2^s·m_(k−s) ⊕
// m_(k−s); direction number k is m_k/2^k, held as m_k shifted to bit 31.
constexpr Matrix sobol_matrix(int s, uint32_t a, std::array<uint32_t, 3> m_init) {
  std::array<uint32_t, 32> m{};
  for (int k = 0; k < s; ++k)
    m[k] = m_init[k];
  for (int k = s; k < 32; ++k) {
    uint32_t v = m[k - s] ^ (m[k - s] << s);
    for (int j = 1; j < s; ++j)
      if ((a >> (s - 1 - j)) & 1) v ^= m[k - j] << j;
    m[k] = v;
  }
  Matrix out{};
  for (int k = 0; k < 32; ++k)
    out[k] = m[k] << (31 - k);
  return out;
}

// Dimensions 2 and 3 are Joe and Kuo's second and third (their file new-joe-kuo-6.21201:
// x² + x + 1 with m = 1, 3; x³ + x + 1 with 1, 3, 1). Dimension 0, the radical inverse, and 1
// (x + 1) need no matrix: render/samplers/sobol_steps.h computes them by bit operations.
constexpr std::array<Matrix, 2> kMatrices = {sobol_matrix(2, 1, {1, 3, 0}),
                                             sobol_matrix(3, 1, {1, 3, 1})};

constexpr uint32_t reversed(uint32_t x) {
  uint32_t r = 0;
  for (int k = 0; k < 32; ++k)
    r |= ((x >> k) & 1u) << (31 - k);
  return r;
}

// The matrix-vector product over GF(2) by chunks of c bits, in the bit-reversed domain the
// scrambles work in: entry [d][j][v] is the XOR of the bit-reversed columns 31 − (c·j + k) of
// dimension d + 2 for the bits k of v, chunk j of a reversed index. So reverse(point(i)) = XOR
// of one lookup per chunk on reverse(i), and a sample needs one reversal per scramble instead
// of two. Scalar code and SSE4.2 read bytes (c = 8, four lookups); lanes that look a word up
// by a register permute read 3 or 4 bits (VPERMD reads an index's low 3 bits over AVX2's 8
// lanes, its low 4 over AVX-512's 16). The last chunk's bits past 31 are never set. Aligned
// so that a 3- or 4-bit chunk's table is one aligned register.
template <int C>
struct ChunkTables {
  static constexpr int kChunks = (32 + C - 1) / C, kEntries = 1 << C;
  alignas(64) std::array<std::array<std::array<uint32_t, kEntries>, kChunks>, 2> t{};
};

// Built incrementally (entry v is entry v without its lowest bit, XOR that bit's column) from
// the reversed columns, to stay well inside compilers' constexpr step limits.
template <int C>
constexpr ChunkTables<C> chunk_tables() {
  std::array<Matrix, 2> columns{};
  for (int d = 0; d < 2; ++d)
    for (int k = 0; k < 32; ++k)
      columns[d][k] = reversed(kMatrices[d][31 - k]);
  ChunkTables<C> out{};
  for (int d = 0; d < 2; ++d)
    for (int j = 0; j < ChunkTables<C>::kChunks; ++j)
      for (uint32_t v = 1; v < uint32_t(ChunkTables<C>::kEntries); ++v) {
        const int bit = C * j + std::countr_zero(v);
        out.t[d][j][v] = out.t[d][j][v & (v - 1)] ^ (bit < 32 ? columns[d][bit] : 0u);
      }
  return out;
}

constexpr ChunkTables<3> kChunks3 = chunk_tables<3>();
constexpr ChunkTables<4> kChunks4 = chunk_tables<4>();
constexpr ChunkTables<8> kBytes = chunk_tables<8>();

uint32_t reverse_bits(uint32_t x) {
  return Num<uint32_t>::reverse_bits(x);
}

// A group's 64-bit seed for a pixel: its low half scrambles the index, its high half seeds the
// components' scrambles. (sobol_lanes_impl.h's group_seeds computes it in lanes.)
uint64_t group_seed_of(uint64_t seed, uint32_t group) {
  return mix64(seed ^ group_salt(group));
}

}  // namespace

namespace detail {
const uint32_t* sobol_byte_tables() {
  return &kBytes.t[0][0][0];
}

const uint32_t* sobol_chunk_tables(int bits) {
  return bits == 3 ? &kChunks3.t[0][0][0] : &kChunks4.t[0][0][0];
}
}  // namespace detail

void SobolBatch::resize(std::size_t rows) {
  size_ = rows;
  if (seed.size() >= padded_size()) return;  // the columns only grow
  seed.resize(padded_size(), 0);
  scramble.resize(padded_size(), 0);
  component.resize(padded_size(), 0);
  for (auto& c : u)
    c.resize(padded_size(), 0);
}

// The lanes compute the group seeds (group_seed_of) and the rest in 32 bits, as sobol_group.
void detail::sobol_groups(const RenderLanes& lanes, uint32_t index, uint32_t group,
                          SobolBatch& batch, unsigned components, const SobolNumbers& numbers) {
  lanes.sobol_groups(reverse_bits(index), group, (components & kAllComponents) | 3u, batch,
                     numbers);
}

void sobol_groups(Isa isa, uint32_t index, uint32_t group, SobolBatch& batch, unsigned components,
                  const SobolNumbers& numbers) {
  detail::sobol_groups(detail::render_lanes(isa), index, group, batch, components, numbers);
}

uint32_t sobol_point(uint32_t index, int d) {
  return reverse_bits(reversed_sobol_point(reverse_bits(index), uint32_t(d)));
}

uint32_t owen_scramble(uint32_t x, uint32_t seed) {
  return reverse_bits(scramble_reversed(reverse_bits(x), seed));
}

std::array<double, 4> sobol_group(uint64_t seed, uint32_t index, uint32_t group) {
  const uint64_t group_seed = group_seed_of(seed, group);
  std::array<double, 4> u;
  sobol_group_bits(reverse_bits(index), uint32_t(group_seed), uint32_t(group_seed >> 32),
                   kAllComponents, [&](uint32_t c, uint32_t bits) { u[c] = sobol_unit(bits); });
  return u;
}

}  // namespace raylane
