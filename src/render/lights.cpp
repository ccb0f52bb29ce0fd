#include "raylane/render/lights.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "raylane/render/texturing.h"

namespace raylane {

namespace {

double area_of(const Scene& scene, PrimRef l) {
  return dispatch(l.tag(), [&](auto kind) {
    using Kind = decltype(kind);
    return Kind::area(scene.table<Kind>(), l.row());
  });
}

// A point on light l as seen from ref: by the solid angle it subtends where the kind can, by
// area otherwise (converted to solid angle). `s` arrives with the light and Le filled in.
template <class Kind>
LightSample sample_kind(const typename Kind::Table& t, uint32_t row, const Vec3d& ref,
                        double choice, double u_part, double u1, double u2, LightSample s) {
  if constexpr (requires { Kind::sample_subtended(t, row, ref, u1, u2); }) {
    if (auto d = Kind::sample_subtended(t, row, ref, u1, u2)) {
      s.wi = d->wi;
      s.dist = d->dist;
      s.p = ref + d->wi * d->dist;
      s.pdf = choice / d->solid_angle;
      return s;
    }
  }
  AreaSample a = Kind::sample_area(t, row, u_part, u1, u2);
  Vec3d to = a.p - ref;
  double d2 = length_squared(to);
  if (!(d2 > 0)) return s;
  s.dist = std::sqrt(d2);
  s.wi = to / s.dist;
  double cos_l = -dot(s.wi, a.n);
  if (Kind::two_sided) cos_l = std::abs(cos_l);
  if (!(cos_l > 0)) return s;  // the back of a solid emitter
  s.p = a.p;
  s.n = a.n;
  s.pdf = choice * d2 / (cos_l * Kind::area(t, row));
  if (!std::isfinite(s.pdf)) s.pdf = 0;
  return s;
}

// The density sample_kind would have had for direction wi from ref, hitting `hit` on light
// row `row`.
template <class Kind>
double pdf_kind(const typename Kind::Table& t, uint32_t row, const Vec3d& ref, const Vec3d& wi,
                const Hit& hit, double choice) {
  if constexpr (requires { Kind::subtended_solid_angle(t, row, ref); }) {
    if (auto omega = Kind::subtended_solid_angle(t, row, ref)) return choice / *omega;
  }
  double d2 = length_squared(hit.surface.p - ref);
  double cos_l = std::abs(dot(wi, hit.surface.ng));
  if (!Kind::two_sided && !hit.front_face) return 0;
  if (!(cos_l > 0)) return 0;
  return choice * d2 / (cos_l * Kind::area(t, row));
}

}  // namespace

LightSampler::LightSampler(const Scene& scene) : scene_(scene) {
  double total = 0;
  std::vector<double> power;
  double env_power = 0;
  if (scene.environment) {
    const EnvironmentSpec& e = *scene.environment;
    env_.emplace(e.image, e.scale, e.rotation);
    Bounds3f b = scene.bounds();
    double radius = b.empty() ? 1.0 : 0.5 * length(Vec3d(b.hi) - Vec3d(b.lo));
    env_power = env_->can_sample() ? env_->power_estimate(std::max(radius, 1e-3)) : 0.0;
    if (!std::isfinite(env_power)) env_power = 0;
    total += env_power;
  }
  for (PrimRef l : scene.lights) {
    const Material& m = scene.materials[scene.material_of(l)];
    Vec3d le(m.emission);
    Vec3d mean_le = m.texture >= 0 ? le * scene.textures[m.texture].mean : le;
    double w = (mean_le.x + mean_le.y + mean_le.z) / 3 * area_of(scene, l);
    if (!(w > 0) || !std::isfinite(w)) continue;
    lights_.push_back(l);
    le_.push_back(le);
    textured_.push_back(m.texture >= 0);
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
  std::sort(by_bits_.begin(), by_bits_.end());
}

std::optional<double> LightSampler::choice_of(PrimRef light) const {
  auto it = std::lower_bound(by_bits_.begin(), by_bits_.end(), std::make_pair(light.bits(), -1.0));
  if (it == by_bits_.end() || it->first != light.bits()) return std::nullopt;
  return it->second;
}

std::size_t LightSampler::pick(double u_light) const {
  std::size_t k = std::upper_bound(cdf_.begin(), cdf_.end(), u_light) - cdf_.begin();
  return std::min(k, cdf_.size() - 1);
}

LightSample LightSampler::sample_environment(double u1, double u2) const {
  LightSample s;
  EnvironmentSample e = env_->sample(u1, u2);
  if (!e.valid()) return s;
  s.wi = e.wi;
  s.dist = std::numeric_limits<double>::infinity();
  s.le = e.le;
  s.pdf = env_choice_ * e.pdf;
  return s;
}

LightSample LightSampler::sample(const Vec3d& ref, double u_light, double u_part, double u1,
                                 double u2) const {
  LightSample s;
  if (empty()) return s;
  std::size_t k = pick(u_light);
  if (k == lights_.size()) return sample_environment(u1, u2);
  PrimRef l = lights_[k];
  s.light = l;
  s.le = le_[k];
  s = dispatch(l.tag(), [&](auto kind) {
    using Kind = decltype(kind);
    return sample_kind<Kind>(scene_.table<Kind>(), l.row(), ref, choice_[k], u_part, u1, u2, s);
  });
  if (textured_[k]) apply_texture(k, s);
  return s;
}

void LightSampler::apply_texture(std::size_t k, LightSample& s) const {
  if (!s.valid()) return;
  const Material& m = scene_.materials[scene_.material_of(lights_[k])];
  s.le = s.le * texture_factor(scene_, m, lights_[k], Surface{s.p, s.n, s.n});
}

void LightSampler::sample_many(Isa isa, LightQueries& q) const {
  q.cone_rows.clear();
  q.cone_choice.clear();
  for (std::size_t r = 0; r < q.size(); ++r) {
    const auto& u = q.u[r];
    LightSample& s = q.out[r];
    std::size_t picked = empty() ? 0 : pick(u[2]);
    if (picked == lights_.size() || lights_[picked].tag() != tag_of<Sphere>) {
      s = sample(q.ref[r], u[2], u[3], u[0], u[1]);
      continue;
    }
    std::size_t k = picked;
    s = LightSample{};  // the row's last wavefront may have left an area sample's normal
    s.light = lights_[k];
    s.le = le_[k];
    s.pdf = 0;
    q.cone_rows.push_back(uint32_t(r));
    q.cone_choice.push_back(choice_[k]);
  }
  ConeBatch& cb = q.cones;
  cb.resize(q.cone_rows.size());
  const SphereTable& spheres = scene_.table<Sphere>();
  for (std::size_t j = 0; j < cb.size(); ++j) {
    uint32_t r = q.cone_rows[j], row = q.out[r].light.row();
    for (int k = 0; k < 3; ++k)
      cb.ref[k][j] = q.ref[r][k], cb.center[k][j] = spheres.center(row)[k];
    cb.radius[j] = spheres.r[row], cb.u1[j] = q.u[r][0], cb.u2[j] = q.u[r][1];
  }
  sample_cones(isa, cb);
  for (std::size_t j = 0; j < cb.size(); ++j) {
    uint32_t r = q.cone_rows[j];
    LightSample& s = q.out[r];
    if (!(cb.solid_angle[j] > 0)) {  // inside the sphere: by area, as sample() does
      s = sample_kind<Sphere>(spheres, s.light.row(), q.ref[r], q.cone_choice[j], q.u[r][3],
                              q.u[r][0], q.u[r][1], s);
      continue;
    }
    s.wi = Vec3d(cb.wi[0][j], cb.wi[1][j], cb.wi[2][j]);
    s.dist = cb.dist[j];
    s.p = q.ref[r] + s.wi * s.dist;
    s.pdf = q.cone_choice[j] / cb.solid_angle[j];
  }
  if (std::find(textured_.begin(), textured_.end(), 1) == textured_.end()) return;
  for (uint32_t r : q.cone_rows) {  // the rest went through sample(), which applied theirs
    std::size_t k = pick(q.u[r][2]);
    if (textured_[k]) apply_texture(k, q.out[r]);
  }
}

double LightSampler::pdf(const Vec3d& ref, const Vec3d& wi, const Hit& hit) const {
  std::optional<double> choice = choice_of(hit.prim);
  if (!choice) return 0;
  PrimRef l = hit.prim;
  return dispatch(l.tag(), [&](auto kind) {
    using Kind = decltype(kind);
    return pdf_kind<Kind>(scene_.table<Kind>(), l.row(), ref, wi, hit, *choice);
  });
}

Vec3d LightSampler::emitted(const Hit& hit) const {
  const Material& m = scene_.materials[scene_.material_of(hit.prim)];
  if (!m.is_light) return {0, 0, 0};
  if (!kind_two_sided(hit.prim.tag()) && !hit.front_face) return {0, 0, 0};
  return Vec3d(m.emission) * texture_factor(scene_, m, hit.prim, hit.surface);
}

}  // namespace raylane
