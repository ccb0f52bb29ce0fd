// The stages of the path tracer's wavefront, in the order path.cpp runs them at each step of a
// thread's wavefront (include from src/render only). Each reads and writes the queues of
// render/wavefront/queues.h; one file per stage, named after it.
#pragma once

#include "raylane/render/camera/camera.h"
#include "raylane/render/film/film.h"
#include "render/wavefront/thread_context.h"

namespace raylane::path_detail {

// camera_rays.cpp: the paths of the tile from (x0, y0) (pixel by pixel in 4×4 blocks) into the
// wavefront's path slots from `first` on, and their jittered camera rays into `into` (cleared
// first). Returns how many paths.
uint32_t make_camera_rays(ThreadContext& ctx, const Camera& cam, uint32_t x0, uint32_t y0,
                          uint32_t first, RayQueue& into);
// camera_rays.cpp: a scene that moves: every ray of `rays` and `shadows` gets its path's time
// (Wavefront::path_time) in its stream's time column, before they are traced. A scene that
// does not move: nothing (its streams have no time column).
void stamp_times(ThreadContext& ctx);
// camera_rays.cpp: the AOVs of this step's camera hits (rays [0, Wavefront::camera_rays)).
void add_camera_aovs(const ThreadContext& ctx, Film& film);

// arrival.cpp: each shadow ray's contribution to its path where its light is unblocked.
void add_unblocked_shadows(ThreadContext& ctx);
// arrival.cpp: where each ray of `rays` arrives. An escaped ray gets the environment, a hit on
// an emitter its emission (both end the path); a hit on a material that may scatter is queued
// in lane_vertices (where the settings and the material allow) or double_vertices, at the
// depth its ray carries (the lane rows with their Sobol seeds and roulette's survival).
void sort_arrivals(ThreadContext& ctx);

// double_vertices.cpp: the double_vertices queue, one by one with the double Bsdf: their
// shadow rays and next rays into next_shadows and next_rays.
void shade_double_vertices(ThreadContext& ctx);

// lane_vertices.cpp: an empty lane_vertices queue with room for `most` vertices.
void start_lane_vertices(ThreadContext& ctx, std::size_t most);
// lane_vertices.cpp: the lane_vertices queue at once, in columns and lanes: their shadow rays
// and next rays into next_shadows and next_rays (through lane_write_back.cpp).
void shade_lane_vertices(ThreadContext& ctx);
// lane_write_back.cpp: the scatter kernel over the lane_vertices rows, whose columns the
// stages before filled (with their light points where `lights`): its rays straight into
// next_shadows and next_rays, the next rays with what they carry of their paths.
void scatter_lane_vertices(ThreadContext& ctx, const VertexRules& rules, bool lights);

}  // namespace raylane::path_detail
