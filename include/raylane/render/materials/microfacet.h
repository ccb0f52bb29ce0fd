// The microfacet distributions other than the course's Phong (render/samplers/sampling.h): GGX and
// Beckman, for the double reference Bsdf (docs/microfacet.md). Each is written in terms of
// cos θm, the cosine of the angle between a microfacet normal m and the surface normal, and
// uses the course's roughness conversion α_g = √(2/(α + 2)) of the Phong exponent α.
//
// Sources: Walter, Marschner, Li, Torrance 2007, "Microfacet Models for Refraction through
// Rough Surfaces": D (eqs. 33 and 25), the Smith G1 (eqs. 34 and 27, the rational fit for
// Beckman) and the warps of m with density D(m)·cos θm (eqs. 35 and 28). The formulas are
// written once over the number type (render/materials/microfacet_steps.h): these are their double
// instantiation, the lane kernel's (src/render/materials/microfacet_lanes_impl.h) their float lanes.
#pragma once

#include "raylane/core/vec_math.h"
#include "raylane/scene/material.h"

namespace raylane {

// The course's conversion, the same α_g for GGX and Beckman: 1 at α = 0, → 0 as α grows.
double microfacet_alpha_g(double alpha);

// D(m) for cos θm (0 where cos θm ≤ 0). ∫ D(m)·cos θm dm = 1 over the hemisphere.
double ggx_d(double cos_m, double alpha_g);
double beckman_d(double cos_m, double alpha_g);

// Smith's G1 of a direction v at microfacet m: 0 where (v·m)/(v·n) ≤ 0 (a back-facing
// microfacet), else GGX's exact 2/(1 + √(1 + α_g² tan²θv)), or the rational fit for Beckman
// with a = 1/(α_g tan θv).
double ggx_g1(double cos_v, double cos_vm, double alpha_g);
double beckman_g1(double cos_v, double cos_vm, double alpha_g);

// A microfacet normal around +z with density D(m)·cos θm, from (u1, u2) in [0, 1]².
glm::dvec3 sample_ggx_normal(double u1, double u2, double alpha_g);
glm::dvec3 sample_beckman_normal(double u1, double u2, double alpha_g);

}  // namespace raylane
