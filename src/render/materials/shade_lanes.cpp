#include "raylane/render/materials/shade_lanes.h"

#include <cmath>

#include "raylane/core/vec_math.h"
#include "raylane/core/warps.h"
#include "render/render_lanes.h"

namespace raylane {

namespace {

constexpr std::size_t kMaxWidth = 16;  // AVX-512's float lanes: every batch is padded to it

// Bsdf's own test (bsdf.cpp, kIndexMatchedContrast): transmission at η_o/η_i within 1e-5 of 1
// is a Dirac lobe, which the double Bsdf samples.
bool index_matched_transmission(const Material& m) {
  bool transmits = length(glm::dvec3(m.kt)) > 0;
  return transmits && std::abs(1 / double(m.ior) - 1) <= 1e-5;
}

}  // namespace

LobeChances lobe_chances(const glm::vec3& kd, const glm::vec3& ks, const glm::vec3& kt) {
  double d = length(glm::dvec3(kd)), r = length(glm::dvec3(ks)), t = length(glm::dvec3(kt));
  double sum = d + r + t;
  if (!(sum > 0)) return {};
  return {float(d / sum), float(r / sum), float(t / sum)};
}

LaneMaterials::LaneMaterials(const std::vector<Material>& materials) {
  // Row 0 must exist: the batch's padding rows gather from it.
  std::vector<Material> rows = materials.empty() ? std::vector<Material>{Material{}} : materials;
  for (const Material& m : rows) {
    for (int k = 0; k < 3; ++k)
      kd[k].push_back(m.kd[k]), ks[k].push_back(m.ks[k]);
    const LobeChances c = lobe_chances(m.kd, m.ks, m.kt);
    pd.push_back(c.pd), pr.push_back(c.pr), pt.push_back(c.pt);
    has_lobes.push_back(pd.back() + pr.back() + pt.back() > 0 ? 1 : 0);
    double a = m.alpha;
    alpha.push_back(m.alpha);
    ior.push_back(m.ior);
    d_scale.push_back(float((a + 2) / (2 * kPi)));
    pm_scale.push_back(float((a + 1) / (2 * kPi)));
    g1_scale.push_back(float(std::sqrt(0.5 * a + 1)));
    microfacet.push_back(float(int(m.microfacet)));
    alpha_g2.push_back(float(2 / (a + 2)));
    if (m.microfacet != Microfacet::kPhong) all_phong = false;
    // A Dirac lobe stays with the double Bsdf (docs/design.md, "Shading in lanes"); a textured
    // Kd is shaded in lanes from its rows' own Kd.
    in_lanes.push_back(index_matched_transmission(m) ? 0 : 1);
    textured.push_back(m.texture >= 0 ? 1 : 0);
    any_textured = any_textured || (m.texture >= 0 && !m.is_light && in_lanes.back());
    route.push_back(m.is_light        ? Route::kEmitter
                    : in_lanes.back() ? Route::kLanes
                                      : Route::kDouble);
    if (in_lanes.back() && (pr.back() > 0 || pt.back() > 0)) lobe_unread = false;
    if (route.back() == Route::kLanes && !has_lobes.back()) any_black = true;
    if (in_lanes.back() && m.kt != glm::vec3(0, 0, 0)) any_absorbing = true;
  }
  count = rows.size();
  const std::size_t padded = (count + kLookupPadding - 1) / kLookupPadding * kLookupPadding;
  for (auto* c3 : {&kd, &ks})
    for (std::vector<float>& c : *c3)
      c.resize(padded, 0.0f);
  for (std::vector<float>* c :
       {&pd, &pr, &pt, &alpha, &ior, &d_scale, &pm_scale, &g1_scale, &microfacet, &alpha_g2})
    c->resize(padded, 0.0f);
}

void ShadeBatch::resize(std::size_t rows) {
  size_ = rows;
  std::size_t padded = (rows + kMaxWidth - 1) / kMaxWidth * kMaxWidth;
  // The columns only grow: shrinking them for a smaller wavefront and regrowing them for the
  // next tile's filled 40 columns again.
  if (material.size() < padded) {
    material.resize(padded, 0);
    for (Column* c : {&u_lobe, &u1, &u2, &pdf, &light_pdf, &pd_at, &pr_at, &pt_at})
      c->resize(padded, 0.5f);
    for (auto* v : {&n, &wo, &light_wi, &wi, &value, &light_f, &kd_at})
      for (int k = 0; k < 3; ++k)
        (*v)[k].resize(padded, k == 2 ? 1.0f : 0.0f);
  }
  // Padding rows: a unit normal and wo, no light direction, numbers in [0, 1); what the
  // kernel makes of them is finite and unread.
  for (std::size_t i = rows; i < padded; ++i) {
    material[i] = 0;
    u_lobe[i] = u1[i] = u2[i] = 0.5f;
    pd_at[i] = pr_at[i] = pt_at[i] = 0.0f;  // black: its lanes are not live
    for (int k = 0; k < 3; ++k) {
      n[k][i] = wo[k][i] = k == 2 ? 1.0f : 0.0f;
      light_wi[k][i] = kd_at[k][i] = 0.0f;
    }
  }
}

void shade_lanes(Isa isa, const LaneMaterials& materials, ShadeBatch& batch) {
  detail::render_lanes(isa).shade(materials, batch);
}

}  // namespace raylane
