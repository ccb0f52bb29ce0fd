// The lane BSDF (render/materials/shade_lanes.h) against the double Bsdf, at every instruction set
// this CPU has: its evaluation within a float error bound away from the model's branch points, its
// samples the double's samples of the same numbers, its directions distributed by the double
// density (chi-square), and no NaN out of degenerate rows.
#include "raylane/render/materials/shade_lanes.h"

#include <gtest/gtest.h>

#include <bit>

#include <cmath>
#include <optional>

#include "chi2.h"
#include "raylane/core/strings.h"
#include "raylane/render/materials/bsdf.h"
#include "raylane/render/samplers/rng.h"
#include "raylane/render/samplers/sampling.h"
#include "raylane/render/samplers/sobol.h"

namespace raylane {
namespace {

constexpr double kU = 0x1p-24;

Material make_material(glm::vec3 kd, glm::vec3 ks, float alpha, glm::vec3 kt = {0, 0, 0},
                       float ior = 1) {
  Material m;
  m.kd = kd, m.ks = ks, m.alpha = alpha, m.kt = kt, m.ior = ior;
  return m;
}

// Every lobe and their mixtures, shininess from rough to 4000, and glass both ways.
std::vector<Material> test_materials() {
  return {make_material({0.7f, 0.5f, 0.3f}, {0, 0, 0}, 0),
          make_material({0, 0, 0}, {0.9f, 0.8f, 0.7f}, 1),
          make_material({0.4f, 0.3f, 0.2f}, {0.3f, 0.3f, 0.3f}, 30),
          make_material({0.1f, 0.1f, 0.1f}, {0.5f, 0.6f, 0.7f}, 4000),
          make_material({0, 0, 0}, {0.04f, 0.04f, 0.04f}, 200, {1, 1, 1}, 1.5f),
          make_material({0, 0, 0}, {0, 0, 0}, 50, {0.9f, 0.8f, 0.9f}, 1.33f),
          make_material({0.2f, 0.2f, 0.2f}, {0.1f, 0.1f, 0.1f}, 5, {0.5f, 0.5f, 0.5f}, 2.4f)};
}

glm::vec3 random_unit(Rng& rng) {
  glm::dvec3 d = sample_uniform_sphere(rng.uniform(), rng.uniform());
  return glm::vec3(normalize(glm::dvec3(glm::vec3(d))));
}

glm::dvec3 column3(const std::array<ShadeBatch::Column, 3>& c, std::size_t i) {
  return {c[0][i], c[1][i], c[2][i]};
}
void set3(std::array<ShadeBatch::Column, 3>& c, std::size_t i, const glm::vec3& v) {
  for (int k = 0; k < 3; ++k)
    c[k][i] = v[k];
}

// A batch of random rows: random material, normal, wo, light direction and numbers.
ShadeBatch random_batch(std::size_t rows, int materials, uint64_t seed) {
  Rng rng(seed);
  ShadeBatch b;
  b.resize(rows);
  for (std::size_t i = 0; i < rows; ++i) {
    b.material[i] = int32_t(rng.uniform() * materials);
    set3(b.n, i, random_unit(rng));
    set3(b.wo, i, random_unit(rng));
    set3(b.light_wi, i, random_unit(rng));
    b.u_lobe[i] = float(rng.uniform()), b.u1[i] = float(rng.uniform());
    b.u2[i] = float(rng.uniform());
  }
  return b;
}

// Whether row i of batch a and row j of batch b hold the same answers bit for bit.
::testing::AssertionResult same_answers(const ShadeBatch& a, std::size_t i, const ShadeBatch& b,
                                        std::size_t j) {
  auto same = [](float x, float y) {
    return std::bit_cast<uint32_t>(x) == std::bit_cast<uint32_t>(y);
  };
  for (auto c : {&ShadeBatch::wi, &ShadeBatch::value, &ShadeBatch::light_f})
    for (int k = 0; k < 3; ++k)
      if (!same((a.*c)[k][i], (b.*c)[k][j]))
        return ::testing::AssertionFailure() << (a.*c)[k][i] << " against " << (b.*c)[k][j];
  if (!same(a.pdf[i], b.pdf[j]) || !same(a.light_pdf[i], b.light_pdf[j]))
    return ::testing::AssertionFailure() << "densities " << a.pdf[i] << ", " << a.light_pdf[i]
                                         << " against " << b.pdf[j] << ", " << b.light_pdf[j];
  return ::testing::AssertionSuccess();
}

// Where the double model has a branch or a singularity within `margin` of this input, float
// may take the other side: such rows are left out of the comparison (and counted).
bool near_a_branch(const Material& m, const glm::dvec3& ns, const glm::dvec3& wo,
                   const glm::dvec3& wi) {
  constexpr double margin = 1e-3;
  double c = dot(ns, wo);
  glm::dvec3 n = c > 0 ? ns : -ns;
  double eta_o = c > 0 ? 1 : m.ior, eta_i = c > 0 ? m.ior : 1, eta = eta_o / eta_i;
  double cos_i = dot(wi, n), cos_o = std::abs(c);
  glm::dvec3 h = cos_i > 0 ? wi + wo : -(wo * eta_o + wi * eta_i);
  double len = length(h), om = dot(wo, h) / len, im = dot(wi, h) / len;
  double k = 1 - eta * eta * (1 - om * om);
  auto a = [&](double cv) {
    return std::sqrt(0.5 * m.alpha + 1) * std::abs(cv) / std::sqrt(1 - cv * cv);
  };
  double den = eta_o * om + eta_i * im;
  return std::abs(cos_i) < margin || cos_o < margin || std::abs(om) < margin ||
         std::abs(im) < margin || std::abs(k) < margin || std::abs(a(cos_i) - 1.6) < margin ||
         std::abs(a(cos_o) - 1.6) < margin || std::abs(dot(h, n)) / len < margin || len < margin ||
         std::abs(den) < margin * (eta_o + eta_i);
}

// The float error bound of one evaluation, relative to the largest channel: 64 roundings for
// the arithmetic of the model (each of its ~40 operations rounds once, and none cancels away
// from the branch points), the lane pow's bound (simd/lane_math.h) at t = α·log2 cos θm, and
// cos θm's own float error (≤ 8·2^-24 absolute: the half vector's sum, normalisation and dot)
// raised to the power α, relative α·8·2^-24/cos θm, which the generalised half vector of
// transmission divides by its length's cancellation. Where the lobe weighs by 1 − F
// (transmission, total internal reflection), Schlick's 1 − F = (1 − Ks)(1 − (1 − |wo·m|)^5)
// cancels: (1 − |wo·m|)^5 carries 20·2^-24 absolute (five times wo·m's 4), relative to 1 − F.
// And the cosines θi and θo, dot products with ≤ 4·2^-24 absolute error, are relative to
// their size (a grazing light direction).
double evaluation_bound(const Material& m, const glm::dvec3& ns, const glm::dvec3& wo,
                        const glm::dvec3& wi) {
  double c = dot(ns, wo);
  glm::dvec3 n = c > 0 ? ns : -ns;
  double eta_o = c > 0 ? 1 : m.ior, eta_i = c > 0 ? m.ior : 1, eta = eta_o / eta_i;
  bool reflect = dot(wi, n) > 0;
  glm::dvec3 h = reflect ? wi + wo : -(wo * eta_o + wi * eta_i);
  double scale = reflect ? 2 : eta_o + eta_i;
  glm::dvec3 mf = normalize(h);
  double cos_m = std::abs(dot(mf, n)), om = std::abs(dot(wo, mf));
  double cancel = scale / length(h);
  double t = m.alpha * std::abs(std::log2(cos_m));
  bool tir = length(glm::dvec3(m.kt)) > 0 && 1 - eta * eta * (1 - om * om) < 0;
  double one_minus_f = 1 - std::pow(1 - om, 5);
  double schlick = !reflect || tir ? 20 / one_minus_f : 0;
  double cosines = 4 / std::abs(dot(wi, n)) + 4 / std::abs(c);
  return kU * (64 + 3 + 3.5 * t + 8 * m.alpha * cancel / cos_m + schlick + cosines);
}

// The lanes flush cos^α θm below 2^-126 to 0 (simd/lane_math.h); scaled by D's (α+2)/(2π)
// ≤ 640 and by 1/(4 cos θo) ≤ 250 or transmission's η²/den² ≤ 2000 (away from the branch
// points), what may vanish is below 2^-126·640·2000 < 1e-31.
constexpr double kFlushed = 1e-31;

TEST(ShadeLanes, EvaluationMatchesTheDoubleBsdf) {
  std::vector<Material> materials = test_materials();
  LaneMaterials lane_materials(materials);
  for (Isa isa : supported_isas()) {
    SCOPED_TRACE(isa_name(isa));
    ShadeBatch b = random_batch(1 << 16, int(materials.size()), 1);
    shade_lanes(isa, lane_materials, b);
    std::size_t compared = 0, skipped = 0;
    double worst = 0;
    for (std::size_t i = 0; i < b.size(); ++i) {
      const Material& m = materials[b.material[i]];
      glm::dvec3 ns = column3(b.n, i), wo = column3(b.wo, i), wi = column3(b.light_wi, i);
      if (near_a_branch(m, ns, wo, wi)) {
        ++skipped;
        continue;
      }
      ++compared;
      BsdfEval ref = Bsdf(m, ns, wo).evaluate(wi);
      glm::dvec3 f = column3(b.light_f, i);
      double bound = evaluation_bound(m, ns, wo, wi);
      double scale = std::max({ref.f.x, ref.f.y, ref.f.z});
      for (int k = 0; k < 3; ++k) {
        ASSERT_LE(std::abs(f[k] - ref.f[k]), bound * scale + kFlushed)
            << "row " << i << " channel " << k;
        worst = std::max(worst, std::abs(f[k] - ref.f[k]) / (bound * scale + kFlushed));
      }
      ASSERT_LE(std::abs(b.light_pdf[i] - ref.pdf), bound * ref.pdf + kFlushed) << "row " << i;
    }
    std::printf("%s: %zu rows compared, %zu near a branch; worst error %.3f of its bound\n",
                std::string(isa_name(isa)).c_str(), compared, skipped, worst);
    EXPECT_LT(skipped, compared / 20);  // the comparison covers the model, not its edges
    EXPECT_GT(worst, 0.0);
  }
}

// The float error of a sampled direction. Diffuse: a few roundings (16·2^-24). Glossy: the
// microfacet's sin θm = √(1 − cos²θm) loses digits where the lobe is narrow, 2·2^-24/sin θm;
// reflecting through m doubles that, refracting scales it by up to 1 + η, and the refraction's
// √k (k = 1 − η²(1 − (wo·m)²)) adds 2^-24·η²/√k.
double direction_bound(const Material& m, const glm::dvec3& ns, const glm::dvec3& wo, double u0,
                       double u1, double u2) {
  double c = dot(ns, wo);
  glm::dvec3 n = c > 0 ? ns : -ns;
  double eta = c > 0 ? 1 / double(m.ior) : double(m.ior);
  double d = length(glm::dvec3(m.kd)),
         total = d + length(glm::dvec3(m.ks)) + length(glm::dvec3(m.kt));
  if (u0 < d / total) return 16 * kU;
  glm::dvec3 local = sample_phong_normal(u1, u2, m.alpha);
  glm::dvec3 mf = Frame(n).to_world(local);
  double sin_m = std::max(1e-6, std::sqrt(std::max(0.0, 1 - local.z * local.z)));
  double om = dot(wo, mf), k = 1 - eta * eta * (1 - om * om);
  double refraction = k > 0 ? eta * eta / std::sqrt(k) : 0;
  return kU * (16 + 2 * (1 + eta) * (16 + 2 / sin_m) + refraction);
}

// The lane sample of the numbers (u0, u1, u2) is the double sample of the same numbers: the
// same lobe, a direction within float's error, and its value and density the evaluation's.
TEST(ShadeLanes, SamplesAreTheDoubleSamplesOfTheSameNumbers) {
  std::vector<Material> materials = test_materials();
  LaneMaterials lane_materials(materials);
  for (Isa isa : supported_isas()) {
    SCOPED_TRACE(isa_name(isa));
    ShadeBatch b = random_batch(1 << 16, int(materials.size()), 2);
    shade_lanes(isa, lane_materials, b);
    std::size_t agree = 0, compared = 0;
    for (std::size_t i = 0; i < b.size(); ++i) {
      const Material& m = materials[b.material[i]];
      glm::dvec3 ns = column3(b.n, i), wo = column3(b.wo, i);
      Bsdf bsdf(m, ns, wo);
      BsdfSample ref = bsdf.sample(b.u_lobe[i], b.u1[i], b.u2[i]);
      bool lane_valid = b.pdf[i] > 0;
      glm::dvec3 wi = column3(b.wi, i);
      if (ref.valid() && near_a_branch(m, ns, wo, ref.wi)) continue;
      ++compared;
      if (lane_valid != ref.valid()) continue;  // counted below: rare at a lobe's very edge
      ++agree;
      if (!ref.valid()) continue;
      ASSERT_LE(length(wi - ref.wi), direction_bound(m, ns, wo, b.u_lobe[i], b.u1[i], b.u2[i]))
          << "row " << i;
      BsdfEval e = bsdf.evaluate(wi);
      double bound = evaluation_bound(m, ns, wo, wi);
      ASSERT_LE(std::abs(b.pdf[i] - e.pdf), bound * e.pdf) << "row " << i;
    }
    EXPECT_GE(agree, compared - compared / 1000) << agree << " of " << compared;
  }
}

// The lane sampler's directions against the double density (tests/render/chi2.h), for a
// diffuse-glossy mixture and a glass seen from outside and from inside.
TEST(ShadeLanes, SampledDirectionsFollowTheDoubleDensity) {
  std::vector<Material> materials = {
      make_material({0.5f, 0.4f, 0.3f}, {0.3f, 0.3f, 0.3f}, 10),
      make_material({0, 0, 0}, {0.04f, 0.04f, 0.04f}, 30, {1, 1, 1}, 1.5f)};
  LaneMaterials lane_materials(materials);
  const glm::dvec3 n(0, 0, 1);
  struct Case {
    int material;
    glm::dvec3 wo{};
  };
  const Case cases[] = {{0, normalize(glm::dvec3(0.5, -0.2, 0.7))},
                        {1, normalize(glm::dvec3(0.3, 0.1, 1))},
                        {1, normalize(glm::dvec3(-0.2, 0.3, -1))}};
  const double level = testing::sidak_level(0.01, 3);
  Isa isa = best_isa();
  for (const Case& c : cases) {
    testing::Chi2Setup setup;
    ShadeBatch b;
    b.resize(std::size_t(setup.samples));
    Rng rng(40 + c.material);
    for (std::size_t i = 0; i < b.size(); ++i) {
      b.material[i] = c.material;
      set3(b.n, i, glm::vec3(n));
      set3(b.wo, i, glm::vec3(c.wo));
      b.u_lobe[i] = float(rng.uniform()), b.u1[i] = float(rng.uniform());
      b.u2[i] = float(rng.uniform());
    }
    shade_lanes(isa, lane_materials, b);
    std::size_t next = 0;
    auto sample = [&](Rng&) -> std::optional<glm::dvec3> {
      std::size_t i = next++;
      if (!(b.pdf[i] > 0)) return std::nullopt;
      return column3(b.wi, i);
    };
    Bsdf bsdf(materials[c.material], n, glm::dvec3(glm::vec3(c.wo)));
    auto pdf = [&](const glm::dvec3& w) { return bsdf.pdf(w); };
    testing::Chi2Result r = testing::chi2_test(setup, sample, pdf, 7);
    EXPECT_FALSE(r.zero_cell_hit);
    EXPECT_GT(r.p_value, level) << "chi2 = " << r.statistic << " with " << r.dof << " dof";
  }
}

// Degenerate rows — wo in the surface plane, no light direction, padding — give zeros, never NaN.
TEST(ShadeLanes, DegenerateRowsGiveNoSampleAndNoNaN) {
  std::vector<Material> materials = test_materials();
  LaneMaterials lane_materials(materials);
  for (Isa isa : supported_isas()) {
    ShadeBatch b = random_batch(37, int(materials.size()), 3);  // 37: partly filled batches
    for (std::size_t i = 0; i < b.size(); i += 2) {
      set3(b.wo, i, glm::vec3(1, 0, 0));
      set3(b.n, i, glm::vec3(0, 0, 1));
      set3(b.light_wi, i, glm::vec3(0, 0, 0));
    }
    shade_lanes(isa, lane_materials, b);
    for (std::size_t i = 0; i < b.size(); ++i) {
      ASSERT_TRUE(std::isfinite(b.pdf[i]) && std::isfinite(b.light_pdf[i])) << i;
      for (int k = 0; k < 3; ++k)
        ASSERT_TRUE(std::isfinite(b.value[k][i]) && std::isfinite(b.light_f[k][i])) << i;
      if (i % 2 == 0) {
        EXPECT_EQ(b.pdf[i], 0.0f) << i;
        EXPECT_EQ(b.light_pdf[i], 0.0f) << i;
      }
    }
  }
}

// Batches whose materials are all diffuse take the diffuse-only path (evaluate_diffuse,
// sample_diffuse); a glossy row among them sends the batch down the general path. The same
// rows give the same answers bit for bit either way: batch `alone` holds diffuse rows only
// (two kd, a few rows black, some edge-on), `mixed` the same rows with a glossy row
// after every third, so that every batch of 4, 8 or 16 lanes holds one. A few rows have
// u0 = 1, which no diffuse lobe takes (pd = 1): their batches sample by the general path.
TEST(ShadeLanes, DiffuseBatchesAreTheGeneralPathsAnswers) {
  LaneMaterials materials({make_material({0.7f, 0.5f, 0.3f}, {0, 0, 0}, 10),
                           make_material({0, 0, 0}, {0, 0, 0}, 10),
                           make_material({0.2f, 0.2f, 0.2f}, {0.5f, 0.5f, 0.5f}, 30)});
  for (Isa isa : supported_isas()) {
    SCOPED_TRACE(std::string(isa_name(isa)));
    ShadeBatch alone = random_batch(61, 1, 17);  // 61: a partly filled last batch
    for (std::size_t i = 7; i < alone.size(); i += 13)
      alone.material[i] = 1;  // black: its batch samples by the general path
    for (std::size_t i = 0; i < alone.size(); i += 9)
      set3(alone.wo, i, glm::vec3(1, 0, 0)), set3(alone.n, i, glm::vec3(0, 0, 1));
    for (std::size_t i = 5; i < alone.size(); i += 23)
      alone.u_lobe[i] = 1.0f;
    ShadeBatch mixed;
    mixed.resize(alone.size() + alone.size() / 3);
    std::vector<std::size_t> at;  // where row i of `alone` is in `mixed`
    for (std::size_t i = 0, j = 0; i < alone.size(); ++i, ++j) {
      if (i > 0 && i % 3 == 0) mixed.material[j++] = 2;  // the glossy row
      at.push_back(j);
      mixed.material[j] = alone.material[i];
      for (auto c : {&ShadeBatch::n, &ShadeBatch::wo, &ShadeBatch::light_wi})
        for (int k = 0; k < 3; ++k)
          (mixed.*c)[k][j] = (alone.*c)[k][i];
      mixed.u_lobe[j] = alone.u_lobe[i], mixed.u1[j] = alone.u1[i], mixed.u2[j] = alone.u2[i];
    }
    shade_lanes(isa, materials, alone);
    shade_lanes(isa, materials, mixed);
    int sampled = 0;
    for (std::size_t i = 0; i < alone.size(); ++i) {
      ASSERT_TRUE(same_answers(alone, i, mixed, at[i])) << "row " << i;
      sampled += alone.pdf[i] > 0;
    }
    EXPECT_GT(sampled, 30);
  }
}

// The lanes read a short material table by register permutes (simd/lane_lookup.h: up to 16
// materials on AVX2, 32 on AVX-512, in one register or two) and a long one by gathers. The
// answers must not depend on which: a batch over the first n materials is shaded with a table
// of n, then with the same materials followed by enough others that every instruction set
// gathers, and the two answer bit for bit. n runs across each register's edge.
TEST(ShadeLanes, ShortMaterialTablesAnswerAsGatheredOnes) {
  std::vector<Material> all;
  for (int i = 0; all.size() < 48; ++i)  // distinct materials: every column differs by row
    for (Material m : test_materials()) {
      m.kd *= 1.0f - 0.01f * float(i), m.ks *= 1.0f - 0.005f * float(i);
      m.alpha += float(i), m.ior += m.ior > 1 ? 0.01f * float(i) : 0.0f;
      all.push_back(m);
    }
  const LaneMaterials gathered(all);
  for (Isa isa : supported_isas()) {
    SCOPED_TRACE(std::string(isa_name(isa)));
    for (int n : {1, 3, 8, 9, 15, 16, 17, 24, 31, 32}) {
      SCOPED_TRACE("materials " + std::to_string(n));
      const LaneMaterials short_table(std::vector<Material>(all.begin(), all.begin() + n));
      ShadeBatch permuted = random_batch(301, n, 40 + n);  // 301: a partly filled last batch
      ShadeBatch reference = permuted;
      shade_lanes(isa, short_table, permuted);
      shade_lanes(isa, gathered, reference);
      int sampled = 0;
      for (std::size_t i = 0; i < permuted.size(); ++i) {
        ASSERT_TRUE(same_answers(permuted, i, reference, i)) << "row " << i;
        sampled += permuted.pdf[i] > 0;
      }
      EXPECT_GT(sampled, 100);
    }
  }
}

// A textured scene's rows carry their own Kd (the material's times the image at the hit) and
// lobe probabilities: each row's evaluation and sample are the double Bsdf's for its material
// with that Kd, within the float bound; untextured rows in the same batch keep their
// material's. Textured materials of every lobe mixture, with factors from black to white.
TEST(ShadeLanes, TexturedRowsAreTheDoubleBsdfOfTheirOwnKd) {
  std::vector<Material> materials = test_materials();
  const std::size_t untextured = materials.size();
  for (std::size_t m = 0; m < untextured; ++m) {
    materials.push_back(materials[m]);
    materials.back().texture = 0;
    if (materials.back().kd == glm::vec3(0, 0, 0)) materials.back().kd = {0.6f, 0.6f, 0.6f};
  }
  LaneMaterials lane_materials(materials);
  ASSERT_TRUE(lane_materials.any_textured);
  for (Isa isa : supported_isas()) {
    SCOPED_TRACE(isa_name(isa));
    ShadeBatch b = random_batch(1 << 15, int(materials.size()), 5);
    b.per_row_kd = true;
    std::vector<Material> row_material(b.size());
    Rng rng(6);
    for (std::size_t i = 0; i < b.size(); ++i) {
      Material m = materials[b.material[i]];
      if (m.texture >= 0) {  // a texel: black one row in 16, else any colour
        bool black = rng.uniform() < 1.0 / 16;
        for (int k = 0; k < 3; ++k)
          m.kd[k] = float(double(m.kd[k]) * (black ? 0.0 : rng.uniform()));
      }
      row_material[i] = m;
      set3(b.kd_at, i, m.kd);
      LobeChances c = lobe_chances(m.kd, m.ks, m.kt);
      b.pd_at[i] = c.pd, b.pr_at[i] = c.pr, b.pt_at[i] = c.pt;
    }
    shade_lanes(isa, lane_materials, b);
    std::size_t compared = 0, samples = 0, agree = 0, black_rows = 0;
    for (std::size_t i = 0; i < b.size(); ++i) {
      const Material& m = row_material[i];
      glm::dvec3 ns = column3(b.n, i), wo = column3(b.wo, i), wi = column3(b.light_wi, i);
      Bsdf bsdf(m, ns, wo);
      if (bsdf.black()) {
        ++black_rows;
        ASSERT_EQ(b.pdf[i], 0.0f) << "row " << i;
        ASSERT_EQ(b.light_pdf[i], 0.0f) << "row " << i;
        continue;
      }
      if (near_a_branch(m, ns, wo, wi)) continue;
      ++compared;
      BsdfEval ref = bsdf.evaluate(wi);
      double bound = evaluation_bound(m, ns, wo, wi);
      double scale = std::max({ref.f.x, ref.f.y, ref.f.z});
      for (int k = 0; k < 3; ++k)
        ASSERT_LE(std::abs(b.light_f[k][i] - ref.f[k]), bound * scale + kFlushed)
            << "row " << i << " channel " << k;
      ASSERT_LE(std::abs(b.light_pdf[i] - ref.pdf), bound * ref.pdf + kFlushed) << "row " << i;
      BsdfSample s = bsdf.sample(b.u_lobe[i], b.u1[i], b.u2[i]);
      if (s.valid() && near_a_branch(m, ns, wo, s.wi)) continue;
      ++samples;
      if ((b.pdf[i] > 0) != s.valid()) continue;
      ++agree;
      if (!s.valid()) continue;
      ASSERT_LE(length(column3(b.wi, i) - s.wi),
                direction_bound(m, ns, wo, b.u_lobe[i], b.u1[i], b.u2[i]))
          << "row " << i;
    }
    EXPECT_GT(compared, b.size() / 2);
    EXPECT_GT(black_rows, 0u);
    EXPECT_GE(agree, samples - samples / 1000) << agree << " of " << samples;
  }
}

TEST(ShadeLanes, IndexMatchedTransmissionStaysWithTheDoubleBsdf) {
  LaneMaterials m({make_material({0, 0, 0}, {0, 0, 0}, 10, {1, 1, 1}, 1.0f),
                   make_material({0, 0, 0}, {0, 0, 0}, 10, {1, 1, 1}, 1.5f),
                   make_material({0.5f, 0.5f, 0.5f}, {0, 0, 0}, 0, {0, 0, 0}, 1.0f)});
  EXPECT_EQ(m.in_lanes, (std::vector<uint8_t>{0, 1, 1}));
}

// lobe_unread holds when every material shaded in lanes is diffuse alone or black, and then
// the lobe number really is unread: the same rows with numbers 0 and just below 1 give the same
// samples bit for bit (the render leaves the number out for such scenes).
TEST(ShadeLanes, LobeNumberIsUnreadOnlyWhenEveryLaneMaterialIsDiffuseAlone) {
  const Material diffuse = make_material({0.7f, 0.5f, 0.3f}, {0, 0, 0}, 10);
  const Material black = make_material({0, 0, 0}, {0, 0, 0}, 10);
  const Material glossy = make_material({0.4f, 0.3f, 0.2f}, {0.3f, 0.3f, 0.3f}, 30);
  const Material glass = make_material({0, 0, 0}, {0, 0, 0}, 50, {0.9f, 0.8f, 0.9f}, 1.33f);
  Material textured_glossy = glossy, textured_diffuse = diffuse;
  textured_glossy.texture = textured_diffuse.texture = 0;  // shaded in lanes, from Kd per row
  const Material matched = make_material({0, 0, 0}, {0, 0, 0}, 10, {1, 1, 1}, 1.0f);  // double
  EXPECT_TRUE(LaneMaterials({diffuse, black, textured_diffuse, matched}).lobe_unread);
  EXPECT_FALSE(LaneMaterials({diffuse, textured_glossy}).lobe_unread);
  EXPECT_FALSE(LaneMaterials({diffuse, glossy}).lobe_unread);
  EXPECT_FALSE(LaneMaterials({glass, diffuse}).lobe_unread);

  const LaneMaterials m({diffuse, make_material({0.2f, 0.9f, 0.2f}, {0, 0, 0}, 2000)});
  for (Isa isa : supported_isas()) {
    SCOPED_TRACE(std::string(isa_name(isa)));
    ShadeBatch low = random_batch(101, 2, 17), high = random_batch(101, 2, 17);
    for (std::size_t i = 0; i < low.size(); ++i)
      low.u_lobe[i] = 0.0f, high.u_lobe[i] = unit_float(1.0);
    shade_lanes(isa, m, low);
    shade_lanes(isa, m, high);
    int sampled = 0;
    for (std::size_t i = 0; i < low.size(); ++i) {
      for (int k = 0; k < 3; ++k) {
        ASSERT_EQ(std::bit_cast<uint32_t>(low.wi[k][i]), std::bit_cast<uint32_t>(high.wi[k][i]));
        ASSERT_EQ(std::bit_cast<uint32_t>(low.value[k][i]),
                  std::bit_cast<uint32_t>(high.value[k][i]));
      }
      ASSERT_EQ(std::bit_cast<uint32_t>(low.pdf[i]), std::bit_cast<uint32_t>(high.pdf[i]));
      sampled += low.pdf[i] > 0;
    }
    EXPECT_GT(sampled, 30);
  }
}

}  // namespace
}  // namespace raylane
