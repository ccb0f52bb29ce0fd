#include "raylane/view/navigation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace raylane {

namespace {

constexpr double kDegrees = std::numbers::pi / 180.0;

// The part of v perpendicular to the unit n.
glm::dvec3 perpendicular(const glm::dvec3& v, const glm::dvec3& n) {
  return v - n * dot(v, n);
}

std::string format_numbers(const char* word, std::initializer_list<double> values) {
  std::string out = word;
  char buf[40];
  for (double v : values) {
    std::snprintf(buf, sizeof buf, " %.17g", v);
    out += buf;
  }
  return out;
}

}  // namespace

glm::dquat quaternion_from_rotation(const glm::dmat3& r) {
  const glm::dmat3 m = glm::transpose(r);  // [row][column]
  double trace = m[0][0] + m[1][1] + m[2][2];
  glm::dquat q{1, 0, 0, 0};
  if (trace > 0) {
    double s = 2 * std::sqrt(trace + 1);  // 4w
    q = {s / 4, (m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s};
  } else if (m[0][0] >= m[1][1] && m[0][0] >= m[2][2]) {
    double s = 2 * std::sqrt(1 + m[0][0] - m[1][1] - m[2][2]);  // 4x
    q = {(m[2][1] - m[1][2]) / s, s / 4, (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s};
  } else if (m[1][1] >= m[2][2]) {
    double s = 2 * std::sqrt(1 + m[1][1] - m[0][0] - m[2][2]);  // 4y
    q = {(m[0][2] - m[2][0]) / s, (m[0][1] + m[1][0]) / s, s / 4, (m[1][2] + m[2][1]) / s};
  } else {
    double s = 2 * std::sqrt(1 + m[2][2] - m[0][0] - m[1][1]);  // 4z
    q = {(m[1][0] - m[0][1]) / s, (m[0][2] + m[2][0]) / s, (m[1][2] + m[2][1]) / s, s / 4};
  }
  // q and −q are the same rotation; w ≥ 0 makes the printed line unique. Normalised, so a
  // matrix a few ulps from orthonormal still gives a unit quaternion.
  double sign = q.w < 0 ? -1.0 : 1.0;
  double n = sign / std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  return {q.w * n, q.x * n, q.y * n, q.z * n};
}

glm::dvec3 camera_right(const CameraSpec& c) {
  return c.rotation * glm::dvec3(1, 0, 0);
}
glm::dvec3 camera_up(const CameraSpec& c) {
  return c.rotation * glm::dvec3(0, 1, 0);
}
glm::dvec3 camera_forward(const CameraSpec& c) {
  return c.rotation * glm::dvec3(0, 0, -1);
}

glm::dvec3 world_up_for(const CameraSpec& c) {
  glm::dvec3 up = camera_up(c);
  int axis = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(up[i]) > std::abs(up[axis])) axis = i;
  glm::dvec3 out(0, 0, 0);
  out[axis] = up[axis] < 0 ? -1.0 : 1.0;
  return out;
}

glm::dmat3 level_rotation(const glm::dvec3& forward, const glm::dvec3& world_up) {
  glm::dvec3 right = normalize(cross(forward, world_up));
  glm::dvec3 up = cross(right, forward);
  glm::dmat3 r{1.0};
  for (int i = 0; i < 3; ++i) {  // columns: R·x = right, R·y = up, R·(−z) = forward
    r[0][i] = right[i];
    r[1][i] = up[i];
    r[2][i] = -forward[i];
  }
  return r;
}

glm::dvec3 turn_direction(const glm::dvec3& dir, double yaw, double pitch,
                          const glm::dvec3& world_up, const glm::dvec3& hint) {
  double elevation = std::asin(std::clamp(dot(dir, world_up), -1.0, 1.0));
  glm::dvec3 heading = perpendicular(dir, world_up);
  // Straight up or down, the image's up (or down) is where the view would tip toward.
  if (length(heading) < 1e-9)
    heading = perpendicular(hint, world_up) * (elevation < 0 ? 1.0 : -1.0);
  heading = normalize(heading);
  // Rodrigues about world up; heading is perpendicular to it, so two terms remain.
  double a = yaw * kDegrees;
  heading = heading * std::cos(a) + cross(world_up, heading) * std::sin(a);
  double limit = kMaxPitchDegrees * kDegrees;
  elevation = std::clamp(elevation + pitch * kDegrees, -limit, limit);
  return normalize(heading * std::cos(elevation) + world_up * std::sin(elevation));
}

CameraSpec fly_move(const CameraSpec& c, const glm::dvec3& step, const glm::dvec3& world_up) {
  CameraSpec out = c;
  out.eye = c.eye + camera_right(c) * step.x + world_up * step.y + camera_forward(c) * step.z;
  return out;
}

CameraSpec fly_look(const CameraSpec& c, double yaw, double pitch, const glm::dvec3& world_up) {
  CameraSpec out = c;
  glm::dvec3 forward = turn_direction(camera_forward(c), yaw, pitch, world_up, camera_up(c));
  out.rotation = level_rotation(forward, world_up);
  return out;
}

CameraSpec orbit(const CameraSpec& c, const glm::dvec3& pivot, double yaw, double pitch,
                 const glm::dvec3& world_up) {
  glm::dvec3 to_pivot = pivot - c.eye;
  double distance = length(to_pivot);
  if (!(distance > 0)) return fly_look(c, yaw, pitch, world_up);
  glm::dvec3 look = turn_direction(to_pivot / distance, yaw, pitch, world_up, camera_up(c));
  CameraSpec out = c;
  out.eye = pivot - look * distance;
  out.rotation = level_rotation(look, world_up);
  return out;
}

double vertical_fov_degrees(double ry) {
  return 2 * std::atan(ry) / kDegrees;
}

double zoom_ry(double ry, double factor) {
  double fov = std::clamp(vertical_fov_degrees(ry) * factor, kMinFovDegrees, kMaxFovDegrees);
  return std::tan(fov / 2 * kDegrees);
}

std::string screen_line(uint32_t width, uint32_t height) {
  return "screen " + std::to_string(width) + " " + std::to_string(height);
}

std::string camera_line(const CameraSpec& c) {
  glm::dquat q = quaternion_from_rotation(c.rotation);
  return format_numbers("camera", {c.eye.x, c.eye.y, c.eye.z, c.ry}) +
         format_numbers(" q", {q.w, q.x, q.y, q.z});
}

}  // namespace raylane
