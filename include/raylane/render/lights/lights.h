// Next-event estimation: picking an emitting primitive and a point on it, and the density of
// having done so for a direction found by BSDF sampling (for MIS). Spheres seen from outside
// are sampled by solid angle (the cone they subtend); boxes and cylinders (on the parts that
// face the point), triangles and the inside of spheres by area, converted to solid angle. A light
// is picked with probability proportional to its power (mean of Le's channels × area), so a scene's
// dim lamps do not take samples from its bright ones.
//
// The environment (`environment`, render/lights/environment.h) is one more light, chosen by its
// power π r² ∫ s·lum(E) dω, r the radius of the scene's bounding sphere (pbrt-v4's estimate of the
// flux an infinite light sends through the scene; docs/design.md, "The environment light").
//
// A light that moves (an emitting mbsphere) is sampled where it is at the path's time: the
// queries carry that time, and the density of a BSDF-sampled hit on it is the one at the ray's
// time (the scene language's spec, "Beyond the course's projects", motion blur).
//
// Emission model: solids (spheres, boxes, cylinders) emit from their outside only; triangles
// emit from both sides. Emitters reflect nothing. A textured emitter's radiance is Le times its
// image at the point; its power is estimated with the image's mean.
#pragma once

#include <array>
#include <optional>
#include <utility>
#include <vector>

#include "raylane/render/lights/environment.h"
#include "raylane/render/lights/light_lanes.h"
#include "raylane/scene/scene.h"
#include "raylane/trace/hit.h"

namespace raylane {

struct LightSample {
  PrimRef light = PrimRef::invalid();  // invalid for the environment
  glm::dvec3 p{};                      // the point on the light
  glm::dvec3 n{};   // its outward normal, where sampled by area (0 from a sphere's cone)
  glm::dvec3 wi{};  // unit direction from the reference point to p
  double dist = 0;  // |p − reference point|; infinite for the environment
  glm::dvec3 le{};  // the radiance arriving along −wi
  double pdf = 0;   // solid-angle density, including the choice of the light
  bool valid() const { return pdf > 0; }
};

// Many shading points' light samples at once (a path tracer's wavefront), in columns, with the
// buffers reused between calls: resize, fill the inputs, call LightSampler::sample_many, read
// the outputs. The cone kernel's batch holds the columns both share, so a sphere light's rows
// are sampled where they stand: no copies into and out of a separate batch. Those columns are
// float, as the float shading reads them: the points, the cone's numbers, the direction, the
// distance and the density (a row sampled one by one in double is rounded into them).
struct LightQueries {
  using Column = std::vector<double>;
  // Inputs: the shading points (cones.ref) and their numbers (cones.u1, cones.u2, u_light,
  // u_part). Outputs: the light (invalid for the environment), the unit direction (cones.wi),
  // the distance (cones.dist), the radiance and the solid-angle density (cones.pdf; 0: no
  // sample).
  ConeBatch cones;
  Column u_light, u_part;
  // The path's time of each row, in [0, 1); empty unless the scene moves (a still scene stores
  // none), and then every row is at mid-shutter, 0.5. Only moving lights read it.
  Column time;
  // Fills `time` from the paths' times (Wavefront::path_time) of rows [0, size()), row r being
  // path[r]'s; clears it when the paths have none.
  void set_times(const uint32_t* path, const std::vector<float>& path_time);
  double time_of(std::size_t r) const { return time.empty() ? 0.5 : time[r]; }
  std::vector<PrimRef> light;
  std::array<std::vector<float>, 3> le;  // rounded to float, as the shading reads it
  // Where a scene's one light is an untextured sphere or box, every row's light and radiance
  // are that light's: sample_many sets them here once and leaves `light` and `le` unfilled (a
  // pass over four columns every step, to write the same values; the scatter kernel takes them
  // as broadcast lanes). Empty otherwise. Read a row's through light_of and le_of.
  struct OneLight {
    PrimRef light;
    std::array<float, 3> le;
  };
  std::optional<OneLight> one_light;
  PrimRef light_of(std::size_t r) const { return one_light ? one_light->light : light[r]; }
  std::array<float, 3> le_of(std::size_t r) const {
    return one_light ? one_light->le : std::array<float, 3>{le[0][r], le[1][r], le[2][r]};
  }
  // Rows [0, n), padded to a multiple of 16 lanes as ConeBatch. The columns only grow.
  void resize(std::size_t n);
  std::size_t size() const { return size_; }
  glm::dvec3 ref(std::size_t r) const { return column3(cones.ref, r); }
  glm::dvec3 wi(std::size_t r) const { return column3(cones.wi, r); }
  double pdf(std::size_t r) const { return cones.pdf[r]; }
  bool valid(std::size_t r) const { return cones.pdf[r] > 0; }
  // Row r's outputs from one sample.
  void set(std::size_t r, const LightSample& s);
  // Which light each row picked, where the lanes sample it: a sphere by its cone, a triangle, a
  // box or a cylinder by area (sample_many's scratch; kEnvironment for the environment, kOneByOne
  // for a light sampled one by one in double).
  static constexpr uint32_t kOneByOne = ~0u, kEnvironment = ~0u - 1;
  std::vector<uint32_t> lane_light;
  // The rows the area kernel samples, and on which light (sample_area_lights' AreaLightRows).
  std::vector<int32_t> area_route, area_index;
  // The rows that picked the environment, and their samples (sample_many's scratch).
  std::vector<uint32_t> environment_rows;
  EnvironmentBatch environment;

 private:
  template <class T>
  static glm::dvec3 column3(const std::array<std::vector<T>, 3>& c, std::size_t r) {
    return {c[0][r], c[1][r], c[2][r]};
  }
  std::size_t size_ = 0;
};

class LightSampler {
 public:
  explicit LightSampler(const Scene& scene);
  bool empty() const { return lights_.empty() && !env_choice_; }
  // How many of (u1, u2, u_light, u_part) sampling reads: the first two always, u_light when
  // there is more than one light to pick, u_part when some light is not a (moving) sphere (a
  // sphere's point needs no part). The others may hold anything.
  int numbers_read() const;

  // A point on a light as seen from `ref` at the path's `time` (where a moving light is then);
  // invalid (pdf 0) when the point faces away.
  LightSample sample(const glm::dvec3& ref, double u_light, double u_part, double u1, double u2,
                     double time) const;
  // sample() for every query, in float lanes where the lanes have the kind's steps
  // (render/lights/light_lanes.h): sphere lights seen from outside by their cones, untextured
  // boxes and cylinders on the parts that face the point, untextured triangles by area. The
  // rest (textured lights but spheres', the inside of spheres) one by one, and the
  // environment's rows together.
  void sample_many(Isa isa, LightQueries& q) const;

  // The density sample() would have had for direction wi from ref at `time` (the ray's),
  // hitting `hit` on a light.
  double pdf(const glm::dvec3& ref, const glm::dvec3& wi, const Hit& hit, double time) const;

  // The radiance a ray sees where it hits an emitter (0 from behind a solid emitter).
  glm::dvec3 emitted(const Hit& hit) const;

  // What a ray that leaves the scene along d sees (0 without an environment), and the density
  // sample() has for that direction (for MIS).
  glm::dvec3 escaped(const glm::dvec3& d) const {
    return env_ ? env_->radiance(d) : glm::dvec3(0, 0, 0);
  }
  double environment_pdf(const glm::dvec3& d) const {
    return env_choice_ * (env_ ? env_->pdf(d) : 0.0);
  }
  // escaped(d) and environment_pdf(d) at once.
  EnvironmentMap::Seen escaped_with_pdf(const glm::dvec3& d) const {
    if (!env_) return {};
    EnvironmentMap::Seen s = env_->seen(d);
    s.pdf *= env_choice_;
    return s;
  }
  // escaped_with_pdf for each of the batch's directions (EnvironmentMap::seen_many).
  void escaped_many(EnvironmentSeenBatch& b) const {
    if (!env_) return b.seen.assign(b.dir.size(), {});
    env_->seen_many(b);
    for (EnvironmentMap::Seen& s : b.seen)
      s.pdf *= env_choice_;
  }
  const EnvironmentMap* environment() const { return env_ ? &*env_ : nullptr; }
  // The probability that sample() picks `light`, or nullopt if it is not one of the lights.
  std::optional<double> choice_of(PrimRef light) const;

 private:
  const Scene& scene_;
  // The index in lights_ of the light u_light picks (by power).
  std::size_t pick(double u_light) const;

  // The environment's direction for the numbers u1, u2 (choice: its choice probability).
  LightSample sample_environment(double u1, double u2) const;
  // The light sample of an environment sample (its density times the choice's).
  LightSample environment_light_sample(const EnvironmentSample& e) const;
  // sample_many's rows that picked the environment (q.environment_rows), all at once.
  void sample_environment_rows(LightQueries& q) const;

  std::optional<EnvironmentMap> env_;
  double env_choice_ = 0;  // its choice probability; it is light index lights_.size()
  std::vector<PrimRef> lights_;
  std::vector<double> cdf_;  // cumulative choice probabilities
  // The guide table of cdf_ (Chen and Asau 1974; Devroye, "Non-Uniform Random Variate
  // Generation", 1986, ch. III): guide_[j] is the first k with cdf_[k] > j / guide_.size(), so
  // that pick starts its search there: with as many entries as lights, the forward search
  // takes at most two comparisons on average (Devroye's bound 1 + n/m), whatever the number of
  // lights; one pick can take more where the powers are very unequal. A binary search over a
  // mesh light's triangles mispredicted at about every step.
  std::vector<uint32_t> guide_;
  std::vector<double> choice_;     // choice probability of lights_[k]
  std::vector<glm::dvec3> le_;     // emission of lights_[k]
  std::vector<uint8_t> textured_;  // lights_[k]'s material has a texture
  // lights_[k]'s route in sample_area_lights (kAreaRouteNone: not sampled there).
  std::vector<int32_t> area_route_;
  // The scene's triangle, box and cylinder columns, for sample_area_lights.
  AreaLightTables area_tables() const;
  // The sample of sample_many's row r, a (moving) sphere light k's, where the kernel's answer
  // needs more: a point inside the sphere (sampled by area) or a texture.
  LightSample finish_sphere_row(const LightQueries& q, std::size_t r, std::size_t k) const;
  // sample_many for a scene whose one light is a sphere, without an environment.
  void sample_one_sphere(Isa isa, LightQueries& q) const;
  // sample_many for a scene whose one light is an untextured box, without an environment.
  void sample_one_box(Isa isa, LightQueries& q) const;
  // The one light and its radiance for every row of q (LightQueries::one_light).
  void set_one_light(LightQueries& q) const;
  // s.le times the light's texture at s.p, for a textured light (a moving one's at `time`).
  void apply_texture(std::size_t k, LightSample& s, double time) const;
  // The centre and radius of sphere light k at `time` (0.5 or anything for a still one), for
  // the cone kernel.
  std::pair<glm::dvec3, double> sphere_at(std::size_t k, double time) const;
  // (PrimRef bits, choice) sorted by bits, for choice_of: a binary search over a few lights is
  // cheaper per sample than a hash lookup.
  std::vector<std::pair<uint32_t, double>> by_bits_;
};

}  // namespace raylane
