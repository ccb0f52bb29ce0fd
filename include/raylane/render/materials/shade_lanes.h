// The course's BSDF (render/materials/bsdf.h) for a whole wavefront of shading points at once, in
// float SIMD lanes (docs/design.md, "Shading in lanes"): each point's sample of the next direction
// and its evaluation toward a sampled light point, with every lobe computed in every lane and the
// lane's choice selected, so that lanes never diverge. The double-precision Bsdf stays the
// reference (tests/render/shade_lanes_test.cpp holds the lanes to it) and shades what the lanes do
// not: index-matched transmission, a Dirac lobe.
//
// Baseline code includes this header; the kernels live in per-ISA translation units
// (src/render/render_lanes_<isa>.cpp), picked at run time through their table
// (src/render/render_lanes.h).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "raylane/scene/material.h"
#include "raylane/simd/isa.h"

namespace raylane {

// The lobe probabilities a material's Kd, Ks and Kt give (|Kd|/s, |Ks|/s, |Kt|/s with s their
// sum, all 0 for a black material), as the double Bsdf computes them, rounded to float.
struct LobeChances {
  float pd = 0, pr = 0, pt = 0;
};
LobeChances lobe_chances(const glm::vec3& kd, const glm::vec3& ks, const glm::vec3& kt);

// The scene's materials as float columns the lanes gather from, with what Bsdf's constructor
// derives per hit computed once per material.
struct LaneMaterials {
  explicit LaneMaterials(const std::vector<Material>& materials);

  // How many materials (rows). The float columns below hold them and zeros after, up to a
  // multiple of kLookupPadding, so that the lanes read a column in whole registers (two of
  // AVX-512's for up to 32 materials) without masking the loads (simd::lookup).
  static constexpr std::size_t kLookupPadding = 32;
  std::size_t count = 0;

  std::array<std::vector<float>, 3> kd, ks;
  std::vector<float> pd, pr, pt;  // lobe probabilities |Kd|/s, |Ks|/s, |Kt|/s (all 0: black)
  std::vector<float> alpha, ior;
  std::vector<float> d_scale;   // (α+2)/(2π): D(m) = d_scale·cos^α θm
  std::vector<float> pm_scale;  // (α+1)/(2π): the warp's density of m
  std::vector<float> g1_scale;  // √(α/2 + 1): the Smith G1 approximation's a = g1_scale·cot θv
  // The microfacet distribution (0 Phong, 1 GGX, 2 Beckman) and GGX's and Beckman's α_g² =
  // 2/(α + 2); read only when some material is not Phong (all_phong false).
  std::vector<float> microfacet, alpha_g2;
  bool all_phong = true;
  std::vector<uint8_t> in_lanes;  // 0: shaded by the double Bsdf (index-matched transmission)
  // 1 where Kd is textured: its rows carry their own Kd and lobe probabilities
  // (ShadeBatch::per_row_kd), Kd times the image at the hit.
  std::vector<uint8_t> textured;
  bool any_textured = false;
  std::vector<uint8_t> has_lobes;  // 1 where pd + pr + pt > 0 (0: the Bsdf is black)
  bool any_black = false;          // some material shaded in lanes has no lobes
  // Some material shaded in lanes transmits (Kt ≠ 0), so Beer's law may weigh a path that
  // arrives at a back face (beer_transmittance is 1 for every other material).
  bool any_absorbing = false;
  // Where a hit on the material goes when the wavefront arrives: it ends its path (an
  // emitter), or it is shaded in lanes or in double (in_lanes), one load per hit. (kNone is no
  // material's: what the arrivals compare against for the lanes when the double shading takes
  // every hit.) 32 bits, so that the arrivals' lanes gather it (render/arrival_lanes.h).
  enum class Route : uint32_t { kEmitter, kLanes, kDouble, kNone };
  std::vector<Route> route;
  // Every material shaded in lanes is diffuse alone or black (pr = pt = 0, so pd is 1 or 0):
  // a sample's lobe number is never read (u < 1 = pd picks the diffuse lobe; black rows are
  // not shaded), and the render does not draw it.
  bool lobe_unread = true;
};

// One wavefront's shading points in float columns. Fill rows [0, size) with resize() and the
// set_* calls, run shade_lanes(), read the outputs. Rows past size up to the lane width are
// padding the kernel may compute and nobody reads.
struct ShadeBatch {
  using Column = std::vector<float>;
  // Inputs.
  std::vector<int32_t> material;   // a row of LaneMaterials with in_lanes = 1
  std::array<Column, 3> n, wo;     // unit shading normal (out of the solid), unit wo
  Column u_lobe, u1, u2;           // the BSDF sample's numbers in [0, 1)
  std::array<Column, 3> light_wi;  // a unit direction to evaluate, or 0 for none
  // Each row's own Kd and lobe probabilities, read instead of its material's where per_row_kd
  // is set (a scene with a textured material: every row's, untextured ones copied from their
  // material, so that a batch reads one kind of column).
  bool per_row_kd = false;
  std::array<Column, 3> kd_at;
  Column pd_at, pr_at, pt_at;
  // Outputs of the sample: direction, f·|cos θi| and density (0: no sample).
  std::array<Column, 3> wi, value;
  Column pdf;
  // Outputs of the evaluation at light_wi: f·|cos θi| and the density sampling has of it.
  std::array<Column, 3> light_f;
  Column light_pdf;

  std::size_t size() const { return size_; }
  // Rows [0, n), padded to a multiple of 16 lanes. Rows below n keep their values (fill them
  // before or after); the columns never shrink (no allocation once grown).
  void resize(std::size_t n);

 private:
  std::size_t size_ = 0;
};

// Samples and evaluates every row of the batch with the kernel compiled for `isa`.
void shade_lanes(Isa isa, const LaneMaterials& materials, ShadeBatch& batch);

}  // namespace raylane
