#include "view_session.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "commands.h"
#include "raylane/core/strings.h"
#include "raylane/image/write_image.h"
#include "raylane/render/camera/camera.h"
#include "raylane/view/navigation.h"
#include "region_option.h"
#include "render_request.h"

namespace raylane::cli {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// Bit for bit: a camera that prints the same line renders the same image.
bool same_camera(const CameraSpec& a, const CameraSpec& b) {
  return std::memcmp(&a.eye, &b.eye, sizeof a.eye) == 0 && std::memcmp(&a.ry, &b.ry, 8) == 0 &&
         std::memcmp(&a.rotation, &b.rotation, sizeof a.rotation) == 0;
}

std::unique_ptr<ViewWorld> make_world(ParsedScene parsed, uint32_t width, uint32_t height) {
  auto world = std::make_unique<ViewWorld>();
  world->parsed = std::move(parsed);
  Scene& scene = world->parsed.scene;
  world->file_camera = scene.camera;
  scene.width = width;
  scene.height = height;
  world->bvh = build_bvh_and_reorder(scene, render_bvh_config(scene));
  // The packet tracer at the widest ISA, like `raylane render`'s defaults.
  world->tracer = std::make_unique<Tracer>(scene, world->bvh, TracerBackend::kPacket, best_isa());
  return world;
}

// view-NNNN: the first NNNN for which no file STEM + extension exists. Never over an existing
// file, so never over an input either.
std::string free_stem(const std::vector<std::string>& extensions) {
  for (int n = 1; n <= 9999; ++n) {
    char stem[32];
    std::snprintf(stem, sizeof stem, "view-%04d", n);
    bool taken = false;
    for (const std::string& ext : extensions)
      taken |= std::filesystem::exists(stem + ext);
    if (!taken) return stem;
  }
  return "";
}

}  // namespace

std::pair<uint32_t, uint32_t> fitted_screen(uint32_t w, uint32_t h) {
  double scale = std::min({1.0, double(kMaxViewWidth) / w, double(kMaxViewHeight) / h});
  if (scale >= 1) return {w, h};
  return {std::max(1u, uint32_t(std::lround(w * scale))),
          std::max(1u, uint32_t(std::lround(h * scale)))};
}

std::string view_mode_name(const ViewMode& mode) {
  return mode ? std::string(raycast_mode_name(*mode)) : "path";
}

ViewSession::ViewSession(const ViewRequest& request, ParsedScene parsed) : request_(request) {
  if (request.threads > 0) omp_set_num_threads(request.threads);
  // The scene's own size: what V prints and S saves. Only the window is scaled to fit.
  uint32_t w = parsed.scene.width, h = parsed.scene.height;
  auto world = make_world(std::move(parsed), w, h);
  std::optional<CameraSpec> camera = world->file_camera;
  adopt(std::move(world), camera);
}

void ViewSession::adopt(std::unique_ptr<ViewWorld> world, std::optional<CameraSpec> camera) {
  world_ = std::move(world);
  world_up_ = world_up_for(*world_->file_camera);
  // Through the printed line, like every camera the view shows; the film starts again in any
  // case, as the tables changed.
  world_->parsed.scene.camera = *camera;
  set_camera(*camera);
  reset_film();
  loaded_times_ = input_times();
  last_watch_ = Clock::now();
}

double ViewSession::scene_size() const {
  Bounds3f b = scene().bounds();
  if (b.empty()) return 1;
  double d = length(glm::dvec3(b.diagonal().x, b.diagonal().y, b.diagonal().z));
  return d > 0 && std::isfinite(d) ? d : 1;
}

bool ViewSession::set_camera(const CameraSpec& c) {
  std::string text = cat(screen_line(width(), height()), "\n", camera_line(c), "\n");
  ParsedScene line = parse_scene(text, "<view camera>");
  if (!line.ok() || !line.scene.camera) return false;  // e.g. flown out of the doubles: stay
  if (same_camera(*line.scene.camera, camera())) return false;
  world_->parsed.scene.camera = *line.scene.camera;
  reset_film();
  return true;
}

std::optional<glm::dvec3> ViewSession::pick(double x, double y) const {
  Camera cam = Camera::from_scene(scene());
  Rayd ray = cam.ray_through(x, height() - y);  // the pixel grid counts y up
  std::vector<Rayd> rays{ray};
  std::vector<Hit> hits;
  world_->tracer->closest(rays, hits);
  if (hits.empty() || !hits[0].hit()) return std::nullopt;
  return ray.o + ray.d * hits[0].t;
}

void ViewSession::set_mode(const ViewMode& mode) {
  if (mode == mode_) return;
  mode_ = mode;
  view_stale_ = true;
  if (!mode_ && film_.passes > 0) image_ = film_.screen_image();
}

void ViewSession::reset_film() {
  film_ = Film{};
  view_stale_ = true;
}

void ViewSession::render_pass() {
  // render_path continues the film from its next pass: after N frames the film holds what
  // `raylane render --spp N` sums, in the same order, so the images agree bit for bit.
  PathSettings settings;  // render's defaults: mis, sobol, float shading, seed 0
  settings.spp = film_.passes + 1;
  settings.region = request_.region;
  PathStats stats;
  auto start = Clock::now();
  render_path(*world_->tracer, settings, &stats, &film_);
  image_ = film_.screen_image();  // a --region's film holds the region alone
  mrays_per_second_ = stats.rays() / std::max(1e-9, seconds_since(start)) * 1e-6;
  previewing_ = false;
}

void ViewSession::render_view(RaycastMode mode) {
  RaycastStats stats;
  auto start = Clock::now();
  image_ = render_raycast(*world_->tracer, mode, &stats, request_.region);
  if (request_.region) image_ = paste_region(image_, *request_.region, width(), height());
  mrays_per_second_ =
      (stats.camera_rays + stats.shadow_rays) / std::max(1e-9, seconds_since(start)) * 1e-6;
}

bool ViewSession::step(bool moving) {
  if (mode_) {
    if (!view_stale_) return false;
    render_view(*mode_);
    view_stale_ = false;
    previewing_ = false;
    return true;
  }
  if (moving) {  // the preview: one ray per pixel instead of a noisy first pass
    render_view(RaycastMode::kLit);
    previewing_ = true;
    return true;
  }
  if (film_.passes >= request_.spp_limit) {
    if (!previewing_) return false;
    image_ = film_.screen_image();
    previewing_ = false;
    return true;
  }
  render_pass();
  return true;
}

Image ViewSession::display_image() const {
  return mode_ ? viewable(image_, *mode_) : image_;
}

std::string ViewSession::scene_lines() const {
  return cat(screen_line(width(), height()), "\n", camera_line(camera()), "\n");
}

Result<std::string> ViewSession::save(double exposure) {
  if (!mode_ && (film_.passes == 0 || previewing_)) {
    if (film_.passes == 0) render_pass();
    image_ = film_.screen_image();
    previewing_ = false;
  }
  if (mode_ && view_stale_) step(false);
  std::vector<std::string> extensions = {".hdr", ".png"};
  if (request_.save_pfm) extensions.push_back(".pfm");
  std::string stem = free_stem(extensions);
  if (stem.empty()) return Error{"view-0001 to view-9999 are all taken"};
  int spp = mode_ ? 1 : film_.passes;
  WriteOptions opts;
  opts.exposure = exposure;
  opts.metadata = {cat("RAYLANE_MODE=", view_mode_name(mode_)), cat("RAYLANE_SPP=", spp)};
  if (!mode_)  // the path tracer's settings, as `raylane render` writes them
    for (std::string& line : path_metadata(PathSettings{}))
      opts.metadata.push_back(std::move(line));
  if (request_.region)
    opts.metadata.push_back(cat("RAYLANE_REGION=", region_text(*request_.region)));
  std::string line = "saved";
  // The 8-bit file's image as shown (HDR and PFM keep the raw values), both cut to a --region
  // as `raylane render --region` cuts them.
  const Image saved = crop_to_region(image_, request_.region);
  const Image shown = crop_to_region(display_image(), request_.region);
  for (const std::string& ext : extensions) {
    std::string path = stem + ext;
    if (Status s = write_image(path, ext == ".png" ? shown : saved, opts); !s)
      return Error{cat(path, ": ", s.error())};
    line += " " + path;
  }
  return cat(line, " (", view_mode_name(mode_), ", ", spp, " spp)");
}

bool ViewSession::reload() {
  auto parsed = load_scene_for_cli(request_.scene_path, request_.lenient, /*quiet=*/false,
                                   request_.overrides);
  if (!parsed) {
    std::fprintf(stderr, "raylane: keeping the scene loaded before\n");
    loaded_times_ = input_times();  // try again at the next change
    return false;
  }
  auto world = make_world(std::move(*parsed), width(), height());
  bool file_camera_moved = !world->file_camera || !world_->file_camera ||
                           !same_camera(*world->file_camera, *world_->file_camera);
  std::optional<CameraSpec> next = file_camera_moved ? world->file_camera : camera();
  adopt(std::move(world), next);
  std::fprintf(stderr, "raylane view: reloaded the scene%s\n",
               file_camera_moved ? ", and its new camera" : "");
  return true;
}

std::vector<std::filesystem::file_time_type> ViewSession::input_times() const {
  std::vector<std::filesystem::file_time_type> times;
  for (const std::string& f : world_->parsed.input_files) {
    std::error_code ec;
    auto t = std::filesystem::last_write_time(f, ec);
    times.push_back(ec ? std::filesystem::file_time_type::min() : t);
  }
  return times;
}

bool ViewSession::inputs_changed() {
  if (seconds_since(last_watch_) < 0.5) return false;
  last_watch_ = Clock::now();
  return input_times() != loaded_times_;
}

}  // namespace raylane::cli
