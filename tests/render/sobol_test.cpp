#include "raylane/render/samplers/sobol.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <random>
#include <vector>

#include "raylane/render/samplers/rng.h"
#include "raylane/render/samplers/sobol_steps.h"

namespace raylane {
namespace {

// The unscrambled points of the first dimensions, from the definition: dimension 0 is the
// radical inverse, dimension 1 (x + 1, m_k = 1, 3, 5, 15, …: direction numbers ½, ¾, ⅝, …)
// starts 0, ½, ¾, ¼, ⅝, ⅛, ⅜, ⅞ (point i is the XOR of the direction numbers of i's bits).
TEST(Sobol, FirstPointsAreTheTextbookOnes) {
  const double d0[] = {0, 0.5, 0.25, 0.75, 0.125, 0.625, 0.375, 0.875};
  const double d1[] = {0, 0.5, 0.75, 0.25, 0.625, 0.125, 0.375, 0.875};
  for (uint32_t i = 0; i < 8; ++i) {
    EXPECT_EQ(sobol_point(i, 0) * 0x1p-32, d0[i]) << i;
    EXPECT_EQ(sobol_point(i, 1) * 0x1p-32, d1[i]) << i;
  }
}

// Every dimension's point is its generator matrix times the index over GF(2) — the XOR of the
// direction numbers of the index's set bits — for many indices. sobol_point takes no matrix:
// dimension 0 reverses bits, 1 runs Lucas's-theorem butterflies, 2 and 3 look up byte tables
// (render/samplers/sobol_steps.h). The direction numbers here are Bratley and Fox's recurrence
// on Joe and Kuo's first three parameter sets, m_k/2^k held at bit 31.
TEST(Sobol, PointsAreTheGeneratorMatrixProducts) {
  auto columns = [](int s, uint32_t a, std::vector<uint32_t> m) {
    for (int k = s; k < 32; ++k) {
      uint32_t v = m[k - s] ^ (m[k - s] << s);
      for (int j = 1; j < s; ++j)
        if ((a >> (s - 1 - j)) & 1) v ^= m[k - j] << j;
      m.push_back(v);
    }
    std::array<uint32_t, 32> out;
    for (int k = 0; k < 32; ++k)
      out[k] = m[k] << (31 - k);
    return out;
  };
  std::array<uint32_t, 32> radical;  // dimension 0, the radical inverse: every m_k = 1
  for (int k = 0; k < 32; ++k)
    radical[k] = 1u << (31 - k);
  const std::array<std::array<uint32_t, 32>, 4> matrix = {
      radical, columns(1, 0, {1}), columns(2, 1, {1, 3}), columns(3, 1, {1, 3, 1})};
  std::mt19937 rng(11);
  for (int trial = 0; trial < 20000; ++trial) {
    const uint32_t index = trial == 0 ? 0xffffffffu : trial < 256 ? uint32_t(trial) : rng();
    for (int d = 0; d < 4; ++d) {
      uint32_t want = 0;
      for (int k = 0; k < 32; ++k)
        if ((index >> k) & 1u) want ^= matrix[d][k];
      ASSERT_EQ(sobol_point(index, d), want) << "index " << index << " dimension " << d;
    }
  }
}

// Components 0 and 1 of a group are a (0, 2)-sequence after scrambling and shuffling: the
// first 2^m points put exactly one point in every cell of every 2^a × 2^(m−a) grid. Random
// points, a wrong direction number or a scramble that is not nested all fail this.
TEST(Sobol, FirstTwoComponentsStratifyEveryDyadicGrid) {
  constexpr int m = 10;
  for (uint64_t seed : {0ull, 1ull, 0x1234567890ull})
    for (uint32_t group : {0u, 1u, 7u}) {
      std::vector<std::array<double, 4>> pts;
      for (uint32_t i = 0; i < (1u << m); ++i)
        pts.push_back(sobol_group(seed, i, group));
      for (int a = 0; a <= m; ++a) {
        std::vector<int> count(1u << m, 0);
        for (const auto& u : pts) {
          uint32_t cx = uint32_t(u[0] * (1u << a)), cy = uint32_t(u[1] * (1u << (m - a)));
          ++count[(cy << a) | cx];
        }
        int empty = 0;
        for (int c : count)
          empty += c == 0;
        EXPECT_EQ(empty, 0) << "seed " << seed << ", group " << group << ", grid 2^" << a << " x 2^"
                            << m - a;
      }
    }
}

// The scramble is nested: values that share their top k bits still share them (each dyadic
// interval moves whole), and it is a bijection on every aligned block.
TEST(Sobol, OwenScrambleMovesDyadicIntervalsWhole) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 20000; ++trial) {
    uint32_t seed = rng(), x = rng(), k = rng() % 32;
    uint32_t y = (x & ~(0xffffffffu >> k)) | (rng() & (0xffffffffu >> k));  // same top k bits
    uint32_t mask = k == 0 ? 0 : ~(0xffffffffu >> k);
    ASSERT_EQ(owen_scramble(x, seed) & mask, owen_scramble(y, seed) & mask);
  }
  std::vector<bool> seen(1 << 12, false);  // the block 0 … 2^12 − 1 lands on one block
  uint32_t block = owen_scramble(0, 77) >> 12;
  for (uint32_t x = 0; x < (1u << 12); ++x) {
    ASSERT_EQ(owen_scramble(x, 77) >> 12, block);
    seen[owen_scramble(x, 77) & 0xfff] = true;
  }
  for (bool s : seen)
    EXPECT_TRUE(s);
}

// χ² of N points in a k×k grid against uniform, as a z-score (Wilson–Hilferty).
double chi2_z(const std::vector<std::pair<double, double>>& pts, int k) {
  std::vector<int> count(k * k, 0);
  for (auto [x, y] : pts)
    ++count[int(y * k) * k + int(x * k)];
  double expected = double(pts.size()) / (k * k), chi2 = 0;
  for (int c : count)
    chi2 += (c - expected) * (c - expected) / expected;
  double dof = k * k - 1.0;
  return (std::cbrt(chi2 / dof) - (1 - 2 / (9 * dof))) / std::sqrt(2 / (9 * dof));
}

// Pairs the net does not stratify together — components of different groups (one path's
// decisions at two bounces), the other components of a group, and one component across
// pixels — are still uniform and independent: χ² on a 16×16 grid within 4.5σ.
TEST(Sobol, OtherPairsAreUniformAndIndependent) {
  constexpr uint32_t n = 1 << 14;
  struct Pair {
    uint64_t seed_a, seed_b;
    uint32_t group_a, group_b;
    int c_a, c_b;
  };
  for (Pair q : {Pair{5, 5, 1, 2, 0, 0}, Pair{5, 5, 3, 8, 1, 0}, Pair{5, 5, 4, 4, 2, 3},
                 Pair{5, 5, 4, 4, 0, 2}, Pair{5, 6, 0, 0, 0, 0}, Pair{9, 10, 2, 2, 1, 1}}) {
    std::vector<std::pair<double, double>> pts;
    for (uint32_t i = 0; i < n; ++i)
      pts.emplace_back(sobol_group(q.seed_a, i, q.group_a)[q.c_a],
                       sobol_group(q.seed_b, i, q.group_b)[q.c_b]);
    double z = chi2_z(pts, 16);
    EXPECT_LT(z, 4.5) << "groups " << q.group_a << "/" << q.group_b << ", components " << q.c_a
                      << "/" << q.c_b << ", seeds " << q.seed_a << "/" << q.seed_b;
  }
}

// A stratified estimate of a smooth integral beats random sampling by far: the mean of
// x·y over the first 1024 points is within 1e-4 of ¼ for each of many pixels (random points
// would stray by ~0.005).
TEST(Sobol, IntegratesASmoothFunctionFarBetterThanRandom) {
  for (uint64_t seed = 0; seed < 50; ++seed) {
    double s = 0;
    for (uint32_t i = 0; i < 1024; ++i) {
      auto u = sobol_group(seed, i, 3);
      s += u[0] * u[1];
    }
    EXPECT_NEAR(s / 1024, 0.25, 1e-4) << seed;
  }
}

}  // namespace
}  // namespace raylane

namespace raylane {
namespace {

// The lanes compute sobol_group for many pixels at once: bit for bit the scalar values, at
// every instruction set this CPU has, for partly filled batches too; asked for fewer
// components (the render's BSDF group asks for 0, 1 and 3: no lobe number, roulette's), the
// same values for those and the rest untouched, in the batch and in the numbers' columns.
TEST(Sobol, LanesGiveTheScalarGroupsBitForBit) {
  for (Isa isa : supported_isas()) {
    SCOPED_TRACE(std::string(isa_name(isa)));
    SobolBatch b;
    b.resize(37);
    for (std::size_t i = 0; i < b.size(); ++i)
      b.seed[i] = mix64(i * 7919 + 3);
    // The numbers' columns: components 0, 2 and 3 as double, 1 and 2 as float; each one row
    // longer than the batch, to see that nothing past its rows is written.
    const double kUnwritten = -1;
    std::array<std::vector<double>, 4> as_double;
    std::array<std::vector<float>, 4> as_float;
    SobolNumbers numbers;
    for (int c : {0, 2, 3})
      numbers.as_double[c] = (as_double[c] = std::vector<double>(b.size() + 1)).data();
    for (int c : {1, 2})
      numbers.as_float[c] = (as_float[c] = std::vector<float>(b.size() + 1)).data();
    const SobolNumbers none;
    for (const SobolNumbers* to : {static_cast<const SobolNumbers*>(&numbers), &none})
      for (uint32_t index : {0u, 1u, 5u, 1000u, 0xfffffffeu})
        for (uint32_t group : {0u, 1u, 9u})
          for (unsigned components :
               {kAllComponents, first_components(3), first_components(2), 0xbu, 0x1u}) {
            for (auto& column : b.u)
              std::fill(column.begin(), column.end(), 0xdeadbeefu);
            for (auto& column : as_double)
              std::fill(column.begin(), column.end(), kUnwritten);
            for (auto& column : as_float)
              std::fill(column.begin(), column.end(), float(kUnwritten));
            sobol_groups(isa, index, group, b, components, *to);
            for (std::size_t i = 0; i <= b.size(); ++i) {
              const bool row = i < b.size();
              std::array<double, 4> ref =
                  row ? sobol_group(b.seed[i], index, group) : std::array<double, 4>{};
              for (int c = 0; c < 4; ++c) {
                const bool computed = row && (c < 2 || (components >> c) & 1u);
                if (row) {
                  ASSERT_EQ(b.u[c][i], computed ? uint32_t(ref[c] * 0x1p32) : 0xdeadbeefu)
                      << "row " << i << " component " << c;
                }
                const bool written = computed && to == &numbers;
                if (!as_double[c].empty()) {
                  ASSERT_EQ(as_double[c][i], written ? ref[c] : kUnwritten)
                      << "row " << i << " component " << c;
                }
                if (!as_float[c].empty()) {
                  ASSERT_EQ(as_float[c][i], written ? unit_float(ref[c]) : float(kUnwritten))
                      << "row " << i << " component " << c;
                }
              }
            }
          }
  }
}

// sobol_unit_float, the lanes' conversion of a component's bits without a double, is
// unit_float(sobol_unit(bits)) bit for bit: on every value of the top 2^24 (where the ties
// round to even and the clamp below 1 acts), every one below 2^25 (exact), every tie between
// floats of every binade above, and a million random bits.
TEST(Sobol, FloatConversionIsTheDoublesRounded) {
  uint64_t differ = 0,
           first = 0;  // counted, not asserted per value: 2^25 failures would take minutes
  auto expect_same = [&](uint32_t bits) {
    if (std::bit_cast<uint32_t>(sobol_unit_float(bits)) ==
        std::bit_cast<uint32_t>(unit_float(sobol_unit(bits))))
      return;
    if (differ++ == 0) first = bits;
  };
  for (uint32_t b = 0xff000000u; b != 0; ++b)
    expect_same(b);
  for (uint32_t b = 0; b < (1u << 25); ++b)
    expect_same(b);
  std::mt19937 rng(5);
  for (int e = 25; e < 32; ++e)  // binade [2^e, 2^(e+1)): floats are 2^(e-23) apart
    for (int i = 0; i < 20000; ++i) {
      const uint32_t step = 1u << (e - 23), at = (1u << e) + (rng() % (1u << 23)) * step;
      expect_same(at + step / 2), expect_same(at + step / 2 - 1), expect_same(at + step / 2 + 1);
    }
  for (int i = 0; i < 1000000; ++i)
    expect_same(uint32_t(rng()));
  EXPECT_EQ(differ, 0u) << "first at bits 0x" << std::hex << first;
}

// A number in [0, 1) as float never rounds up to 1: the float shading's lobe choice (u < pd,
// pd = 1 for a diffuse-only material) would take a lobe the material does not have. The
// largest Sobol number, (2^32 − 1)·2^-32, rounds to 1 as a plain float.
TEST(Sobol, FloatNumbersStayBelowOne) {
  const double largest = 0xffffffffu * 0x1p-32;
  ASSERT_EQ(float(largest), 1.0f);  // what unit_float is for
  EXPECT_LT(unit_float(largest), 1.0f);
  EXPECT_EQ(unit_float(largest), std::nextafter(1.0f, 0.0f));
  for (double u : {0.0, 0x1p-40, 0.25, 0.5, 1 - 0x1p-24, 1 - 0x1p-24 - 0x1p-30})
    EXPECT_EQ(unit_float(u), float(u)) << u;  // rounded to nearest below the tie at 1 − 2^-25
  for (double u : {1 - 0x1p-25, 1 - 0x1p-26})
    EXPECT_EQ(unit_float(u), std::nextafter(1.0f, 0.0f)) << u;
  // The lanes' float columns too: a pixel seed (found by search) whose group 2, sample 3 has a
  // lobe number that rounds to 1 as a plain float.
  const uint64_t seed = 0xebddb830daf658b8ull;
  const double u = sobol_group(seed, 3, 2)[2];
  ASSERT_EQ(float(u), 1.0f);
  for (Isa isa : supported_isas()) {
    SCOPED_TRACE(std::string(isa_name(isa)));
    SobolBatch b;
    b.resize(20);
    for (std::size_t i = 0; i < b.size(); ++i)
      b.seed[i] = i == 13 ? seed : mix64(i);
    std::vector<float> lobe(b.size());
    SobolNumbers to;
    to.as_float[2] = lobe.data();
    sobol_groups(isa, 3, 2, b, first_components(3), to);
    EXPECT_EQ(lobe[13], unit_float(u));
    EXPECT_LT(lobe[13], 1.0f);
  }
}

}  // namespace
}  // namespace raylane
