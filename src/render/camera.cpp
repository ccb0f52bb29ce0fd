#include "raylane/render/camera.h"

namespace raylane {

Camera Camera::from_scene(const Scene& scene) {
  Camera c;
  const CameraSpec& spec = *scene.camera;
  c.eye = spec.eye;
  c.right = spec.rotation * Vec3d(1, 0, 0);
  c.up = spec.rotation * Vec3d(0, 1, 0);
  c.forward = spec.rotation * Vec3d(0, 0, -1);
  c.width = scene.width;
  c.height = scene.height;
  c.ry = spec.ry;
  c.rx = spec.ry * double(scene.width) / double(scene.height);
  return c;
}

}  // namespace raylane
