// Points on sphere lights by the cone each subtends, and on box, cylinder and triangle lights by
// area, for a whole wavefront's vertices at once in float SIMD lanes (the scalar routines were a
// large share of a render's profile: docs/design.md, "Shading in lanes"). The cones' steps are
// sphere_cone's (prims/sphere_cone.h), whose double instance is Sphere::sample_subtended:
// tests/render/light_lanes_test.cpp holds the lanes to its scalar float instance bit for bit,
// and that to the double one within float's error bound. The boxes' steps are box_faces.h's and
// area_light_sample.h's, the double shading's text: tests/render/box_light_lanes_test.cpp holds
// the lanes to their scalar float instance bit for bit, and that to what the box shows within
// its standard error; the triangles' and cylinders' steps are triangle_light.h's and
// cylinder_light.h's, held the same way by tests/render/area_light_lanes_test.cpp.
// LightSampler::sample_many routes sphere lights and untextured box, triangle and cylinder
// lights here.
//
// Baseline code includes this header; the kernel lives in the per-ISA translation units
// src/render/render_lanes_<isa>.cpp, picked at run time through their table
// (src/render/render_lanes.h).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "raylane/simd/isa.h"

namespace raylane {

// Fill rows [0, size) after resize(), run sample_cones(), read the outputs. Rows past size up
// to the lane width are padding the kernel computes and nobody reads.
struct ConeBatch {
  using Column = std::vector<float>;
  // Inputs: the shading point, the sphere, the two numbers of the cone's warp and the
  // probability of having chosen this light.
  std::array<Column, 3> ref, center;
  Column radius, u1, u2, choice;
  // Outputs: the unit direction, the distance to the sphere along it, the cone's solid angle
  // and the sample's density choice / solid angle; solid_angle and pdf 0 where ref is not
  // outside the sphere (the caller samples by area).
  std::array<Column, 3> wi;
  Column dist, solid_angle, pdf;
  // Optional, for the float BSDF that is evaluated toward the light next: where wi_float[0] is
  // set, rows [0, size) of these three float columns get wi where the sample is valid (pdf > 0)
  // and 0 where it is not. The kernel writes them with its other outputs, saving the caller a
  // pass (LightQueries::set keeps them for rows finished one by one). The caller points them at
  // columns of at least the padded size.
  std::array<float*, 3> wi_float{};

  std::size_t size() const { return size_; }
  // Rows [0, n), padded to a multiple of 16 lanes; keeps the capacity.
  void resize(std::size_t n);

 private:
  std::size_t size_ = 0;
};

// The one sphere every row samples (a scene whose only light is a sphere): its centre, radius
// and choice broadcast into the lanes, so that the batch's center, radius and choice columns
// need no filling and are not read.
struct ConeSphere {
  std::array<float, 3> center;
  float radius, choice;
};

// The cones of rows [0, batch.size()), each about its own sphere (the batch's columns) or all
// about `every_row`.
void sample_cones(Isa isa, ConeBatch& batch, const ConeSphere* every_row = nullptr);

// The one box every row samples (a scene whose only light is a box): its corners and choice.
struct ConeBox {
  std::array<float, 3> lo, hi;
  float choice;
};

// Points on the faces of `box` that face each row's point (prims/box_faces.h), rows [0,
// batch.size()), from the batch's ref, u1 and u2 and the face's number u_part (a column of at
// least the padded size, rounded to float): the batch's wi, dist and pdf (0: no sample), and
// wi_float where set. The centres, radii, choices and solid angles are neither read nor
// written.
void sample_box_faces(Isa isa, ConeBatch& batch, const double* u_part, const ConeBox& box);

// The rows sample_area_lights draws, and on which light: each row's route and its light's row
// in that kind's table. Columns of at least the batch's padded size.
inline constexpr int32_t kAreaRouteNone = 0, kAreaRouteTriangle = 1, kAreaRouteBox = 2,
                         kAreaRouteCylinder = 3;
struct AreaLightRows {
  const int32_t* route = nullptr;  // kAreaRoute*: None leaves the row as it is
  const int32_t* index = nullptr;  // the light's row in its table; any valid row for None
};

// The float columns of the emitting kinds' tables (prims/triangle.h, prims/box.h,
// prims/cylinder.h): a kind's
// columns may be null where no row takes its route.
struct AreaLightTables {
  std::array<const float*, 9> triangle{};  // p0x, p0y, p0z, p1x, … p2z
  std::array<const float*, 6> box{};       // lox, loy, loz, hix, hiy, hiz
  std::array<const float*, 8> cylinder{};  // bx, by, bz, ux, uy, uz, h, r
};

// Points by area on each row's own triangle (prims/triangle_light.h, two-sided), box (on the
// faces that face the row's point, prims/box_faces.h) or cylinder (on the cap and the half side
// that face it, prims/cylinder_light.h), for the rows [0, batch.size()) that
// rows.route sends there: the batch's wi, dist and pdf (0: no sample), and wi_float where set,
// from its ref, u1, u2 and choice, and the face's number u_part (rounded to float). Every other
// row's outputs are left as they were.
void sample_area_lights(Isa isa, ConeBatch& batch, const double* u_part, const AreaLightRows& rows,
                        const AreaLightTables& tables);

}  // namespace raylane
