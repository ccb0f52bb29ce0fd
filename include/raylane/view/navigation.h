// Moving a camera by hand (`raylane view`): fly (move in the camera's frame, turn by yaw and
// pitch), orbit about a pivot, zoom the field of view, and the camera written back as a scene
// line. Pure math on CameraSpec (scene/scene.h: right = R·x, up = R·y, forward = R·(−z)).
//
// "Up" is a world axis: the one of ±x, ±y, ±z nearest the scene camera's own up (Z for the
// course's scenes). Turning keeps the camera level against it: the right vector stays
// perpendicular to world up, so no roll creeps in however long one looks around.
#pragma once

#include <cstdint>
#include <string>

#include "raylane/core/rotation.h"
#include "raylane/scene/scene.h"

namespace raylane {

// The unit quaternion of a rotation matrix, with w ≥ 0 (Shoemake 1985, "Animating rotation with
// quaternion curves": from the trace when it is positive, else from the largest diagonal
// element, so the division is never by a small number). glm::mat3_cast inverts it.
glm::dquat quaternion_from_rotation(const glm::dmat3& r);

glm::dvec3 camera_right(const CameraSpec& c);    // R·x
glm::dvec3 camera_up(const CameraSpec& c);       // R·y
glm::dvec3 camera_forward(const CameraSpec& c);  // R·(−z)

// The world axis (±x, ±y, ±z) nearest the camera's up vector.
glm::dvec3 world_up_for(const CameraSpec& c);

// The level rotation that looks along the unit `forward`: right = forward × up normalised (so
// horizontal), camera up = right × forward. `forward` must not be parallel to `world_up`.
glm::dmat3 level_rotation(const glm::dvec3& forward, const glm::dvec3& world_up);

// Pitch never goes past this many degrees from the horizon, so the view never flips over.
inline constexpr double kMaxPitchDegrees = 89.0;

// The unit direction `dir` turned `yaw` degrees about world up (positive: to the left, the
// right-hand rule about up) and `pitch` degrees toward up (positive: up), its elevation clamped
// to ±kMaxPitchDegrees. `hint` (a unit vector in the image's up direction) gives the heading
// when `dir` is straight up or down.
glm::dvec3 turn_direction(const glm::dvec3& dir, double yaw, double pitch,
                          const glm::dvec3& world_up, const glm::dvec3& hint);

// Moves the eye by step.x along right, step.y along world up and step.z along forward (scene
// units); the orientation is unchanged.
CameraSpec fly_move(const CameraSpec& c, const glm::dvec3& step, const glm::dvec3& world_up);

// Turns the view (yaw, pitch as in turn_direction); the result is level.
CameraSpec fly_look(const CameraSpec& c, double yaw, double pitch, const glm::dvec3& world_up);

// Moves the eye on the sphere about `pivot` through the eye: the direction from the eye to the
// pivot turns by (yaw, pitch) as in turn_direction, the distance stays, and the camera looks at
// the pivot, level.
CameraSpec orbit(const CameraSpec& c, const glm::dvec3& pivot, double yaw, double pitch,
                 const glm::dvec3& world_up);

// The field of view scaled by `factor` (ry = tan of half the vertical field), kept within
// [kMinFovDegrees, kMaxFovDegrees].
inline constexpr double kMinFovDegrees = 1.0, kMaxFovDegrees = 160.0;
double zoom_ry(double ry, double factor);
double vertical_fov_degrees(double ry);

// Scene lines that a scene file or `--set` reads back: "screen W H" and
// "camera ex ey ez ry q w x y z", every number with 17 significant digits, so that the parsed
// numbers are the printed ones bit for bit.
std::string screen_line(uint32_t width, uint32_t height);
std::string camera_line(const CameraSpec& c);

}  // namespace raylane
