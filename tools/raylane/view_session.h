// `raylane view`'s state, without the window: the scene and its BVH, the camera, the film that
// accumulates path-traced passes while the camera stands still, and what the keys do to them
// (save, print, reload). The window and its events are in view_loop.cpp.
#pragma once

#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "raylane/bvh/bvh.h"
#include "raylane/core/limits.h"
#include "raylane/core/memory.h"
#include "raylane/render/film/film.h"
#include "raylane/render/path.h"
#include "raylane/render/raycast.h"
#include "raylane/scene/parser.h"

namespace raylane::cli {

struct ViewRequest {
  std::optional<std::string> scene_path;  // none: the built-in course scene
  std::vector<std::string> overrides;     // --set lines
  bool lenient = false;
  int spp_limit = 4096;   // passes after which the film stops growing
  int threads = 0;        // 0: all cores
  bool save_pfm = false;  // saves also write view-NNNN.pfm (32-bit float: exact comparisons)
  std::optional<PixelRegion> region;  // --region: rendered alone (black around it), and saved
  uint64_t image_memory = default_image_memory();  // --image-memory, in bytes
  bool image_memory_chosen = false;                // --image-memory given
};

// The largest window: a larger screen is shown scaled down to fit, keeping its shape (the
// render keeps the scene's size).
inline constexpr uint32_t kMaxViewWidth = 1280, kMaxViewHeight = 800;

// The window for a scene screen of w × h: its size, or scaled down into the largest window.
std::pair<uint32_t, uint32_t> fitted_screen(uint32_t w, uint32_t h);

// What is shown: the path tracer (nothing) or one ray-casting view.
using ViewMode = std::optional<RaycastMode>;
std::string view_mode_name(const ViewMode& mode);

// A loaded scene with what tracing it needs; held by pointer, since the tracer refers to both.
struct ViewWorld {
  ParsedScene parsed;
  Bvh bvh;
  std::unique_ptr<Tracer> tracer;
  std::optional<CameraSpec> file_camera;  // the camera the scene itself gives
};

class ViewSession {
 public:
  // `parsed` is the scene as loaded (with the --set lines); its camera and screen become the
  // view's, through the printed lines (see set_camera).
  ViewSession(const ViewRequest& request, ParsedScene parsed);

  uint32_t width() const { return scene().width; }
  uint32_t height() const { return scene().height; }
  const Scene& scene() const { return world_->parsed.scene; }
  const CameraSpec& camera() const { return *scene().camera; }
  glm::dvec3 world_up() const { return world_up_; }
  double scene_size() const;  // the diagonal of the scene's bounds (1 for an empty scene)

  // The camera becomes `c` as `raylane render --set '<camera_line(c)>'` reads it (bit for bit:
  // the line is printed and parsed back), so the view and a render of the printed lines are
  // the same image. A changed camera empties the film; returns whether it changed.
  bool set_camera(const CameraSpec& c);
  // The point that the ray through window pixel (x, y) (from the top left) hits first, if any.
  std::optional<glm::dvec3> pick(double x, double y) const;

  const ViewMode& mode() const { return mode_; }
  void set_mode(const ViewMode& mode);

  // One frame's work: a path pass into the film (or, while `moving`, the `lit` preview), or
  // the ray-casting view when it is out of date. Returns false when there was nothing to do
  // (the film is at the pass limit, the view is up to date).
  bool step(bool moving);
  const Image& image() const { return image_; }  // linear; what `s` saves as HDR
  Image display_image() const;                   // what the window and the PNG show
  int passes() const { return film_.passes; }
  bool previewing() const { return previewing_; }
  double mrays_per_second() const { return mrays_per_second_; }

  // "screen W H\ncamera ..." — what `v` prints.
  std::string scene_lines() const;
  // Writes view-NNNN.hdr and view-NNNN.png (and .pfm with --pfm; the first NNNN with none of
  // them present) in the working directory, atomically; returns the line to print:
  // "saved view-0001.hdr view-0001.png (path, 16 spp)".
  Result<std::string> save(double exposure);

  // Reloads the scene file (after an edit: `r`, or when watch() sees a newer file). A scene
  // with errors keeps the old one. The camera stays where it was, unless the file's own
  // camera line changed, which then wins.
  bool reload();
  // Whether a file the scene was read from changed since it was loaded (checked at most twice
  // a second; cheap to call every frame).
  bool inputs_changed();

 private:
  void adopt(std::unique_ptr<ViewWorld> world, std::optional<CameraSpec> camera);
  void reset_film();
  void render_pass();
  void render_view(RaycastMode mode);
  std::vector<std::filesystem::file_time_type> input_times() const;

  ViewRequest request_;
  std::unique_ptr<ViewWorld> world_;
  glm::dvec3 world_up_{0, 0, 1};
  ViewMode mode_;
  Film film_;
  Image image_;
  bool view_stale_ = true;  // the ray-casting view needs rendering
  bool previewing_ = false;
  double mrays_per_second_ = 0;
  std::vector<std::filesystem::file_time_type> loaded_times_;
  std::chrono::steady_clock::time_point last_watch_;
};

}  // namespace raylane::cli
