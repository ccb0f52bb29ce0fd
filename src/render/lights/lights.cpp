#include "raylane/render/lights/lights.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <type_traits>

#include "raylane/prims/area_light_sample.h"
#include "raylane/render/materials/texturing.h"

namespace raylane {

namespace {

double area_of(const Scene& scene, PrimRef l) {
  return dispatch(l.tag(), [&](auto kind) {
    using Kind = decltype(kind);
    return Kind::area(scene.table<Kind>(), l.row());
  });
}

// A kind's emitter sampling at `time`: a moving kind's routines take the time, a still kind's
// do not.
template <class Kind>
std::optional<SubtendedSample> subtended_at(const typename Kind::Table& t, uint32_t row,
                                            const glm::dvec3& ref, double u1, double u2,
                                            double time) {
  if constexpr (requires { Kind::sample_subtended(t, row, ref, u1, u2, time); })
    return Kind::sample_subtended(t, row, ref, u1, u2, time);
  else if constexpr (requires { Kind::sample_subtended(t, row, ref, u1, u2); })
    return Kind::sample_subtended(t, row, ref, u1, u2);
  else
    return std::nullopt;
}

template <class Kind>
std::optional<double> solid_angle_at(const typename Kind::Table& t, uint32_t row,
                                     const glm::dvec3& ref, double time) {
  if constexpr (requires { Kind::subtended_solid_angle(t, row, ref, time); })
    return Kind::subtended_solid_angle(t, row, ref, time);
  else if constexpr (requires { Kind::subtended_solid_angle(t, row, ref); })
    return Kind::subtended_solid_angle(t, row, ref);
  else
    return std::nullopt;
}

// A point by area on the part of the light that faces ref (a box's faces toward it:
// Box::sample_area_seen_from) where the kind knows it, else on all of it.
template <class Kind>
AreaSample area_sample_at(const typename Kind::Table& t, uint32_t row, const glm::dvec3& ref,
                          double u_part, double u1, double u2, double time) {
  if constexpr (requires { Kind::sample_area_seen_from(t, row, ref, u_part, u1, u2); })
    return Kind::sample_area_seen_from(t, row, ref, u_part, u1, u2);
  else if constexpr (requires { Kind::sample_area(t, row, u_part, u1, u2, time); })
    return Kind::sample_area(t, row, u_part, u1, u2, time);
  else
    return Kind::sample_area(t, row, u_part, u1, u2);
}

// The area area_sample_at draws from: the density's denominator, for the sample and for MIS.
// A kind samples the part it shows and counts that part's area, or neither: one without the
// other would bias both.
template <class Kind>
double area_sampled(const typename Kind::Table& t, uint32_t row, const glm::dvec3& ref) {
  static_assert(
      requires { Kind::area_seen_from(t, row, ref); } ==
      requires { Kind::sample_area_seen_from(t, row, ref, 0.5, 0.5, 0.5); });
  if constexpr (requires { Kind::area_seen_from(t, row, ref); })
    return Kind::area_seen_from(t, row, ref);
  else
    return Kind::area(t, row);
}

// A point on light l as seen from ref at `time`: by the solid angle it subtends where the kind
// can, by area otherwise (converted to solid angle). `s` arrives with the light and Le filled
// in.
template <class Kind>
LightSample sample_kind(const typename Kind::Table& t, uint32_t row, const glm::dvec3& ref,
                        double choice, double u_part, double u1, double u2, double time,
                        LightSample s) {
  if (auto d = subtended_at<Kind>(t, row, ref, u1, u2, time)) {
    s.wi = d->wi;
    s.dist = d->dist;
    s.p = ref + d->wi * d->dist;
    s.pdf = choice / d->solid_angle;
    return s;
  }
  const AreaSample a = area_sample_at<Kind>(t, row, ref, u_part, u1, u2, time);
  const AreaLightSample<double, glm::dvec3> x =
      area_light_sample<Kind::two_sided>(ref, a.p, a.n, area_sampled<Kind>(t, row, ref), choice);
  if (!(x.pdf > 0)) return s;  // the back of a solid emitter, or the point at ref
  s.wi = x.wi;
  s.dist = x.dist;
  s.p = a.p;
  s.n = a.n;
  s.pdf = x.pdf;
  return s;
}

// The route of light l in sample_area_lights (render/lights/light_lanes.h): the kinds whose
// steps the area kernel has; kAreaRouteNone for the others.
int32_t area_route_of(PrimRef l) {
  return dispatch(l.tag(), [](auto kind) {
    using Kind = decltype(kind);
    if constexpr (std::is_same_v<Kind, Triangle>)
      return kAreaRouteTriangle;
    else if constexpr (std::is_same_v<Kind, Box>)
      return kAreaRouteBox;
    else if constexpr (std::is_same_v<Kind, Cylinder>)
      return kAreaRouteCylinder;
    else
      return kAreaRouteNone;
  });
}

// The density sample_kind would have had for direction wi from ref at `time`, hitting `hit` on
// light row `row`.
template <class Kind>
double pdf_kind(const typename Kind::Table& t, uint32_t row, const glm::dvec3& ref,
                const glm::dvec3& wi, const Hit& hit, double time, double choice) {
  if (auto omega = solid_angle_at<Kind>(t, row, ref, time)) return choice / *omega;
  double d2 = length_squared(hit.surface.p - ref);
  double cos_l = std::abs(dot(wi, hit.surface.ng));
  if (!Kind::two_sided && !hit.front_face) return 0;
  if (!(cos_l > 0)) return 0;
  const double area = area_sampled<Kind>(t, row, ref);
  if (!(area > 0)) return 0;  // ref in the closed solid: nothing it sees is drawn
  return choice * d2 / (cos_l * area);
}

}  // namespace

LightSampler::LightSampler(const Scene& scene) : scene_(scene) {
  double total = 0;
  std::vector<double> power;
  double env_power = 0;
  if (scene.environment) {
    const EnvironmentSpec& e = *scene.environment;
    env_.emplace(e.texels, e.scale, e.rotation);
    Bounds3f b = scene.bounds();
    double radius = b.empty() ? 1.0 : 0.5 * length(glm::dvec3(b.hi) - glm::dvec3(b.lo));
    env_power = env_->can_sample() ? env_->power_estimate(std::max(radius, 1e-3)) : 0.0;
    if (!std::isfinite(env_power)) env_power = 0;
    total += env_power;
  }
  for (PrimRef l : scene.lights) {
    const Material& m = scene.materials[scene.material_of(l)];
    glm::dvec3 le(m.emission);
    glm::dvec3 mean_le = m.texture >= 0 ? le * scene.textures[m.texture].mean : le;
    double w = (mean_le.x + mean_le.y + mean_le.z) / 3 * area_of(scene, l);
    if (!(w > 0) || !std::isfinite(w)) continue;
    lights_.push_back(l);
    le_.push_back(le);
    textured_.push_back(m.texture >= 0);
    area_route_.push_back(m.texture >= 0 ? kAreaRouteNone : area_route_of(l));
    power.push_back(w);
    total += w;
  }
  double acc = 0;
  for (std::size_t k = 0; k < lights_.size(); ++k) {
    acc += power[k] / total;
    cdf_.push_back(acc);
    choice_.push_back(power[k] / total);
    by_bits_.emplace_back(lights_[k].bits(), power[k] / total);
  }
  if (env_power > 0) {  // the environment comes last: u_light above every shape's share
    env_choice_ = env_power / total;
    cdf_.push_back(1.0);
  }
  if (!cdf_.empty()) cdf_.back() = 1.0;
  guide_.resize(cdf_.size());
  for (std::size_t j = 0, k = 0; j < guide_.size(); ++j) {
    const double at = double(j) / double(guide_.size());
    while (k + 1 < cdf_.size() && !(cdf_[k] > at))
      ++k;
    guide_[j] = uint32_t(k);
  }
  std::sort(by_bits_.begin(), by_bits_.end());
}

std::optional<double> LightSampler::choice_of(PrimRef light) const {
  auto it = std::lower_bound(by_bits_.begin(), by_bits_.end(), std::make_pair(light.bits(), -1.0));
  if (it == by_bits_.end() || it->first != light.bits()) return std::nullopt;
  return it->second;
}

int LightSampler::numbers_read() const {
  for (PrimRef l : lights_)  // a (moving) sphere's point needs no part
    if (l.tag() != tag_of<Sphere> && l.tag() != tag_of<MovingSphere>) return 4;
  return cdf_.size() > 1 ? 3 : 2;
}

// The first k with cdf_[k] > u_light (the last where none is), as std::upper_bound finds it,
// from the guide table's entry for u_light's share: that entry's bound is at most u_light, so
// the answer is at or after it; a step back covers a product u_light · size rounded up onto
// the next entry.
std::size_t LightSampler::pick(double u_light) const {
  const std::size_t last = cdf_.size() - 1;
  const double at = u_light * double(guide_.size());  // NaN: entry 0, and the search ends last
  const std::size_t j = at > 0 ? (at < double(last) ? std::size_t(at) : last) : 0;
  std::size_t k = guide_[j];
  while (k > 0 && cdf_[k - 1] > u_light)
    --k;
  while (k < last && !(cdf_[k] > u_light))
    ++k;
  return k;
}

LightSample LightSampler::sample_environment(double u1, double u2) const {
  return environment_light_sample(env_->sample(u1, u2));
}

void LightSampler::sample_environment_rows(LightQueries& q) const {
  const std::vector<uint32_t>& rows = q.environment_rows;
  if (rows.empty()) return;
  EnvironmentBatch& b = q.environment;
  b.resize(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i)
    b.u1[i] = q.cones.u1[rows[i]], b.u2[i] = q.cones.u2[rows[i]];
  env_->sample_many(b);
  for (std::size_t i = 0; i < rows.size(); ++i)
    q.set(rows[i], environment_light_sample(b.out[i]));
}

LightSample LightSampler::environment_light_sample(const EnvironmentSample& e) const {
  LightSample s;
  if (!e.valid()) return s;
  s.wi = e.wi;
  s.dist = std::numeric_limits<double>::infinity();
  s.le = e.le;
  s.pdf = env_choice_ * e.pdf;
  return s;
}

LightSample LightSampler::sample(const glm::dvec3& ref, double u_light, double u_part, double u1,
                                 double u2, double time) const {
  LightSample s;
  if (empty()) return s;
  std::size_t k = pick(u_light);
  if (k == lights_.size()) return sample_environment(u1, u2);
  PrimRef l = lights_[k];
  s.light = l;
  s.le = le_[k];
  s = dispatch(l.tag(), [&](auto kind) {
    using Kind = decltype(kind);
    return sample_kind<Kind>(scene_.table<Kind>(), l.row(), ref, choice_[k], u_part, u1, u2, time,
                             s);
  });
  if (textured_[k]) apply_texture(k, s, time);
  return s;
}

void LightSampler::apply_texture(std::size_t k, LightSample& s, double time) const {
  if (!s.valid()) return;
  const Material& m = scene_.materials[scene_.material_of(lights_[k])];
  Surface surface{s.p, s.n, s.n};
  if (lights_[k].tag() == tag_of<MovingSphere>) {
    // Its texture is looked up by the normal (moving_sphere.h), which a cone's sample leaves 0.
    glm::dvec3 n = normalize(s.p - sphere_at(k, time).first);
    surface = Surface{s.p, n, n};
  }
  s.le = s.le * texture_factor(scene_, m, lights_[k], surface);
}

std::pair<glm::dvec3, double> LightSampler::sphere_at(std::size_t k, double time) const {
  const uint32_t row = lights_[k].row();
  if (lights_[k].tag() == tag_of<MovingSphere>) {
    const MovingSphereTable& t = scene_.table<MovingSphere>();
    return {t.center_at(row, time), double(t.r[row])};
  }
  const SphereTable& t = scene_.table<Sphere>();
  return {glm::dvec3(t.center(row)), double(t.r[row])};
}

void LightQueries::set_times(const uint32_t* path, const std::vector<float>& path_time) {
  if (path_time.empty()) return time.clear();
  time.resize(size_);
  for (std::size_t r = 0; r < size_; ++r)
    time[r] = path_time[path[r]];
}

void LightQueries::resize(std::size_t n) {
  size_ = n;
  cones.resize(n);
  // Padded as the cones are: the scatter kernel reads le in whole batches of float lanes.
  const std::size_t padded = (n + 15) / 16 * 16;
  if (u_light.size() < padded) {
    for (Column* c : {&u_light, &u_part})
      c->resize(padded);
    for (std::vector<float>& c : le)
      c.resize(padded);
    light.resize(padded);
    lane_light.resize(padded);
    area_route.resize(padded);
    area_index.resize(padded);
  }
}

void LightQueries::set(std::size_t r, const LightSample& s) {
  light[r] = s.light;
  // Rounded to float: a density below float's range is no sample, as the float shading reads it.
  const float pdf = float(s.pdf);
  cones.pdf[r] = pdf;
  cones.dist[r] = float(s.dist);
  for (int k = 0; k < 3; ++k)
    cones.wi[k][r] = float(s.wi[k]), le[k][r] = float(s.le[k]);
  if (cones.wi_float[0])  // ConeBatch::wi_float, as the kernel writes it
    for (int k = 0; k < 3; ++k)
      cones.wi_float[k][r] = pdf > 0 ? float(s.wi[k]) : 0.0f;
}

// The one light is a sphere (and no environment): every row's cone is about the same sphere,
// which the kernel broadcasts (ConeSphere) rather than reading columns filled or looked up row
// by row (the loops in sample_many were 5 % of the course scene's render, the fills 2 %). The
// answers are those of the general path bit for bit: the same values, the same kernel.
void LightSampler::sample_one_sphere(Isa isa, LightQueries& q) const {
  ConeBatch& cb = q.cones;
  const std::size_t n = q.size();
  const SphereTable& spheres = scene_.table<Sphere>();
  const uint32_t row = lights_[0].row();
  const glm::vec3 center = spheres.center(row);
  const ConeSphere every_row{{center.x, center.y, center.z}, spheres.r[row], float(choice_[0])};
  sample_cones(isa, cb, &every_row);
  const bool textured = textured_[0];  // read once: q.set's stores may alias a uint8_t
  if (textured) {  // each row's radiance its own (sample_many left one_light empty)
    for (std::size_t r = 0; r < n; ++r)
      q.set(r, finish_sphere_row(q, r, 0));
    return;
  }
  set_one_light(q);
  // The rows the kernel gave no cone (a point inside the sphere or too close to it for float)
  // are rare: blocks of 16 rows are tested at once, in a loop without a branch per row.
  const float* solid_angle = cb.solid_angle.data();
  constexpr std::size_t kBlock = 16;
  for (std::size_t b = 0; b < n; b += kBlock) {
    const std::size_t end = std::min(n, b + kBlock);
    unsigned any = 0;  // an unsigned OR, which the compiler vectorises (a bool's it did not)
    for (std::size_t r = b; r < end; ++r)
      any |= unsigned(!(solid_angle[r] > 0));
    if (!any) continue;
    for (std::size_t r = b; r < end; ++r)
      if (!(solid_angle[r] > 0)) q.set(r, finish_sphere_row(q, r, 0));
  }
}

// The one light is a box (and no environment), not textured: every row's point on the faces
// it sees in float lanes (prims/box_faces.h), where sample() draws it one by one in double.
// The same steps (prims/box_faces.h, prims/area_light_sample.h) in float: the lanes are their
// scalar float instance bit for bit, and that instance estimates what the box shows
// (tests/render/box_light_lanes_test.cpp).
void LightSampler::sample_one_box(Isa isa, LightQueries& q) const {
  const BoxTable& boxes = scene_.table<Box>();
  const uint32_t row = lights_[0].row();
  const glm::vec3 lo = boxes.lo(row), hi = boxes.hi(row);
  const ConeBox box{{lo.x, lo.y, lo.z}, {hi.x, hi.y, hi.z}, float(choice_[0])};
  sample_box_faces(isa, q.cones, q.u_part.data(), box);
  set_one_light(q);
}

// Every row's light and radiance: the one light's (sample_one_sphere, sample_one_box), the
// same for every row. The sphere's rows without a cone (q.set, finish_sphere_row) write their
// own columns as well, with the same values.
void LightSampler::set_one_light(LightQueries& q) const {
  q.one_light =
      LightQueries::OneLight{lights_[0], {float(le_[0][0]), float(le_[0][1]), float(le_[0][2])}};
}

void LightSampler::sample_many(Isa isa, LightQueries& q) const {
  q.one_light.reset();  // set again by the one light's samplers
  if (lights_.size() == 1 && cdf_.size() == 1 && lights_[0].tag() == tag_of<Sphere>)
    return sample_one_sphere(isa, q);
  if (lights_.size() == 1 && cdf_.size() == 1 && lights_[0].tag() == tag_of<Box> && !textured_[0])
    return sample_one_box(isa, q);
  if (lights_.empty() && env_choice_ > 0) {
    // The environment is the only light: every row samples it, without a pick or a cone's
    // inputs (which only the cone kernel reads, and no row has a cone).
    q.environment_rows.resize(q.size());
    std::iota(q.environment_rows.begin(), q.environment_rows.end(), 0u);
    return sample_environment_rows(q);
  }
  ConeBatch& cb = q.cones;
  const std::size_t n = q.size();
  // Each row's light. A sphere's rows get its center (a moving one's at the row's time),
  // radius and choice for the cone kernel; a triangle's, a box's or a cylinder's rows their
  // route, row and choice for the area kernel. The other rows get a unit sphere two units above
  // their point (what the cone kernel makes of them is overwritten below).
  bool any_cone = false, any_area = false;
  q.environment_rows.clear();
  for (std::size_t r = 0; r < n; ++r) {
    std::size_t k = empty() ? lights_.size() : pick(q.u_light[r]);
    const bool environment = k == lights_.size() && env_choice_ > 0;
    if (environment) q.environment_rows.push_back(uint32_t(r));
    const bool cone = k < lights_.size() && (lights_[k].tag() == tag_of<Sphere> ||
                                             lights_[k].tag() == tag_of<MovingSphere>);
    const int32_t area = k < lights_.size() ? area_route_[k] : kAreaRouteNone;
    q.lane_light[r] = cone || area != kAreaRouteNone ? uint32_t(k)
                      : environment                  ? LightQueries::kEnvironment
                                                     : LightQueries::kOneByOne;
    q.area_route[r] = area;
    q.area_index[r] = area != kAreaRouteNone ? int32_t(lights_[k].row()) : 0;
    any_cone = any_cone || cone;
    any_area = any_area || area != kAreaRouteNone;
    auto [center, radius] =
        cone ? sphere_at(k, q.time_of(r))
             : std::pair<glm::dvec3, double>(q.ref(r) + glm::dvec3(0, 0, 2), 1.0);
    for (int c = 0; c < 3; ++c)
      cb.center[c][r] = float(center[c]);
    cb.radius[r] = float(radius);
    cb.choice[r] = cone || area != kAreaRouteNone ? float(choice_[k]) : 1.0f;
  }
  // Direction, distance and density of every cone row (none under an environment alone), then
  // of every area row.
  if (any_cone) sample_cones(isa, cb);
  if (any_area)
    sample_area_lights(isa, cb, q.u_part.data(), {q.area_route.data(), q.area_index.data()},
                       area_tables());
  for (std::size_t r = 0; r < n; ++r) {
    const uint32_t k = q.lane_light[r];
    if (k == LightQueries::kEnvironment) continue;  // sampled together below
    if (k == LightQueries::kOneByOne) {
      q.set(r, sample(q.ref(r), q.u_light[r], q.u_part[r], cb.u1[r], cb.u2[r], q.time_of(r)));
      continue;
    }
    q.light[r] = lights_[k];
    for (int c = 0; c < 3; ++c)
      q.le[c][r] = float(le_[k][c]);
    if (q.area_route[r] != kAreaRouteNone) continue;       // the area kernel's answer stands
    if (cb.solid_angle[r] > 0 && !textured_[k]) continue;  // the cone kernel's answer stands
    q.set(r, finish_sphere_row(q, r, k));
  }
  sample_environment_rows(q);
}

AreaLightTables LightSampler::area_tables() const {
  const TriangleTable& t = scene_.table<Triangle>();
  const BoxTable& b = scene_.table<Box>();
  AreaLightTables out;
  out.triangle = {t.p0x.data(), t.p0y.data(), t.p0z.data(), t.p1x.data(), t.p1y.data(),
                  t.p1z.data(), t.p2x.data(), t.p2y.data(), t.p2z.data()};
  out.box = {b.lox.data(), b.loy.data(), b.loz.data(), b.hix.data(), b.hiy.data(), b.hiz.data()};
  const CylinderTable& c = scene_.table<Cylinder>();
  out.cylinder = {c.bx.data(), c.by.data(), c.bz.data(), c.ux.data(),
                  c.uy.data(), c.uz.data(), c.h.data(),  c.r.data()};
  return out;
}

LightSample LightSampler::finish_sphere_row(const LightQueries& q, std::size_t r,
                                            std::size_t k) const {
  const ConeBatch& cb = q.cones;
  LightSample s;
  s.light = lights_[k];
  s.le = le_[k];
  const double time = q.time_of(r);
  if (!(cb.solid_angle[r] > 0)) {  // inside the sphere: by area, as sample() does
    s = s.light.tag() == tag_of<MovingSphere>
            ? sample_kind<MovingSphere>(scene_.table<MovingSphere>(), s.light.row(), q.ref(r),
                                        choice_[k], q.u_part[r], cb.u1[r], cb.u2[r], time, s)
            : sample_kind<Sphere>(scene_.table<Sphere>(), s.light.row(), q.ref(r), choice_[k],
                                  q.u_part[r], cb.u1[r], cb.u2[r], time, s);
  } else {
    s.wi = q.wi(r);
    s.dist = cb.dist[r];
    s.p = q.ref(r) + s.wi * s.dist;
    s.pdf = cb.pdf[r];
  }
  if (textured_[k]) apply_texture(k, s, time);
  return s;
}

double LightSampler::pdf(const glm::dvec3& ref, const glm::dvec3& wi, const Hit& hit,
                         double time) const {
  std::optional<double> choice = choice_of(hit.prim);
  if (!choice) return 0;
  PrimRef l = hit.prim;
  return dispatch(l.tag(), [&](auto kind) {
    using Kind = decltype(kind);
    return pdf_kind<Kind>(scene_.table<Kind>(), l.row(), ref, wi, hit, time, *choice);
  });
}

glm::dvec3 LightSampler::emitted(const Hit& hit) const {
  const Material& m = scene_.materials[scene_.material_of(hit.prim)];
  if (!m.is_light) return {0, 0, 0};
  if (!kind_two_sided(hit.prim.tag()) && !hit.front_face) return {0, 0, 0};
  return glm::dvec3(m.emission) * texture_factor(scene_, m, hit.prim, hit.surface);
}

}  // namespace raylane
