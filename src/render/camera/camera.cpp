#include "raylane/render/camera/camera.h"

#include "raylane/core/warps.h"

namespace raylane {

Camera Camera::from_scene(const Scene& scene) {
  Camera c;
  const CameraSpec& spec = *scene.camera;
  c.eye = spec.eye;
  c.right = spec.rotation * glm::dvec3(1, 0, 0);
  c.up = spec.rotation * glm::dvec3(0, 1, 0);
  c.forward = spec.rotation * glm::dvec3(0, 0, -1);
  c.width = scene.width;
  c.height = scene.height;
  c.ry = spec.ry;
  c.rx = spec.ry * double(scene.width) / double(scene.height);
  c.lens_radius = scene.lens.radius;
  c.focus = scene.lens.focus;
  return c;
}

Rayd Camera::ray_through_lens(double x, double y, double u1, double u2) const {
  if (!has_lens()) return ray_through(x, y);
  glm::dvec3 in_focus = eye + pinhole_offset<double, glm::dvec3>(*this, x, y) * focus;
  glm::dvec3 disc = sample_concentric_disc(u1, u2) * lens_radius;
  glm::dvec3 o = eye + right * disc.x + up * disc.y;
  return {o, normalize(in_focus - o)};
}

}  // namespace raylane
