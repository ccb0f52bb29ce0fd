// `raylane view`'s window (SDL2): events to camera moves and commands, one frame of work per
// loop, the image shown through the window surface (no GPU: plain pixels work anywhere,
// Xvfb included). Built only when CMake finds SDL2 (RAYLANE_HAVE_SDL2).
#include <SDL.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "commands.h"
#include "raylane/core/strings.h"
#include "raylane/image/png.h"
#include "raylane/view/navigation.h"
#include "view.h"

namespace raylane::cli {

namespace {

using Clock = std::chrono::steady_clock;

// The modes keys 1..8 choose, in order; M steps through them.
const ViewMode kModeKeys[] = {std::nullopt,         RaycastMode::kLit,     RaycastMode::kNormal,
                              RaycastMode::kAlbedo, RaycastMode::kDepth,   RaycastMode::kUv,
                              RaycastMode::kId,     RaycastMode::kPosition};
constexpr int kModeCount = 8;

constexpr double kExposureStep = 0.5;           // stops per [ or ]
constexpr double kZoomStep = 1.1;               // field of view factor per wheel notch or + -
constexpr double kSpeedPerSize = 0.25;          // scene diagonals per second
constexpr double kStillSeconds = 0.2;           // the camera stands still after this long unmoved
constexpr double kLongestStep = 0.1;            // seconds: a slow frame must not fling the camera
constexpr double kOrbitDegreesPerHeight = 180;  // a drag across the window's height

enum class Drag { kNone, kLook, kOrbit };

// Frames per second of the frames that did work, smoothed: each frame's own time, from the
// end of its events to its image on screen, so a pause (idle, converged) between frames does
// not count, and a frame slower than a second (a 1080p pass on 2 cores) still does.
struct FrameRate {
  double seconds = 0;  // per frame
  void frame(double dt) { seconds = seconds == 0 ? dt : 0.8 * seconds + 0.2 * dt; }
  double fps() const { return seconds > 0 ? 1 / seconds : 0; }
};

struct Controls {
  double exposure = 0;
  bool left_orbits = false;  // O
  Drag drag = Drag::kNone;
  glm::dvec3 pivot{};
  bool quit = false;
  bool redraw = true;
  double window_height = 1;  // pixels: a drag is measured against the window, not the render
};

// SDL state, released in reverse order of creation.
struct Sdl {
  SDL_Window* window = nullptr;
  ~Sdl() {
    if (window) SDL_DestroyWindow(window);
    SDL_Quit();
  }
};

int mode_index(const ViewMode& mode) {
  for (int i = 0; i < kModeCount; ++i)
    if (kModeKeys[i] == mode) return i;
  return 0;
}

// The window shows what the PNG would hold: pixel·2^exposure, sRGB-encoded to 8 bits.
void present(SDL_Window* window, const Image& image, double exposure) {
  SDL_Surface* target = SDL_GetWindowSurface(window);
  if (!target || image.width == 0) return;
  std::vector<uint8_t> rgb(image.rgb.size());
  const float gain = float(std::exp2(exposure));
  for (std::size_t i = 0; i < rgb.size(); ++i)
    rgb[i] = srgb_encode_8bit(image.rgb[i] * gain);
  SDL_Surface* source =
      SDL_CreateRGBSurfaceWithFormatFrom(rgb.data(), int(image.width), int(image.height), 24,
                                         int(image.width * 3), SDL_PIXELFORMAT_RGB24);
  if (!source) return;
  SDL_BlitScaled(source, nullptr, target, nullptr);  // converts to the window's format
  SDL_FreeSurface(source);
  SDL_UpdateWindowSurface(window);
}

std::string title(const ViewSession& s, const std::string& name, const Controls& c,
                  const FrameRate& rate_of_frames) {
  std::string what = s.mode()         ? view_mode_name(s.mode())
                     : s.previewing() ? std::string("lit preview")
                                      : cat("path ", s.passes(), " spp");
  char rate[48];
  std::snprintf(rate, sizeof rate, "%.2f Mrays/s | %.1f fps", s.mrays_per_second(),
                rate_of_frames.fps());
  char exposure[32];
  std::snprintf(exposure, sizeof exposure, "exposure %+.1f", c.exposure);
  return cat("raylane view: ", name, " | ", what, " | ", rate, " | ", exposure, " | ",
             c.left_orbits ? "orbit" : "look", " | fov ",
             int(std::lround(vertical_fov_degrees(s.camera().ry))));
}

// Where an orbit turns about: the surface at the centre of the view, or, looking at nothing,
// the point in front as far away as the scene's centre.
glm::dvec3 orbit_pivot(const ViewSession& s) {
  if (auto hit = s.pick(s.width() / 2.0, s.height() / 2.0)) return *hit;
  const CameraSpec& c = s.camera();
  Bounds3f b = s.scene().bounds();
  glm::dvec3 centre =
      b.empty() ? c.eye : glm::dvec3(b.centroid().x, b.centroid().y, b.centroid().z);
  double d = std::max(length(centre - c.eye), 1e-3 * s.scene_size());
  return c.eye + camera_forward(c) * d;
}

void save(ViewSession& s, const Controls& c) {
  auto saved = s.save(c.exposure);
  if (!saved) {
    std::fprintf(stderr, "raylane: cannot save: %s\n", saved.error().c_str());
    return;
  }
  std::printf("%s\n", saved->c_str());
  std::fflush(stdout);
}

// A key that is a command (not a move): the course window's letters, S saves and Q quits (the
// moves are on the arrow keys, so no letter is both), with P and Ctrl+S, Esc and Ctrl+Q too.
void on_key(const SDL_KeyboardEvent& key, ViewSession& s, Controls& c, CameraSpec& camera) {
  bool ctrl = key.keysym.mod & KMOD_CTRL;
  SDL_Keycode k = key.keysym.sym;
  if (k == SDLK_ESCAPE || k == SDLK_q) c.quit = true;
  if (k == SDLK_s || k == SDLK_p) save(s, c);
  if (k == SDLK_v) {
    std::fputs(s.scene_lines().c_str(), stdout);
    std::fflush(stdout);
  }
  if (k == SDLK_r && !ctrl) s.reload(), camera = s.camera(), c.redraw = true;
  if (k >= SDLK_1 && k < SDLK_1 + kModeCount) s.set_mode(kModeKeys[k - SDLK_1]);
  if (k == SDLK_m) s.set_mode(kModeKeys[(mode_index(s.mode()) + 1) % kModeCount]);
  if (k == SDLK_o) c.left_orbits = !c.left_orbits, c.redraw = true;
  if (k == SDLK_LEFTBRACKET) c.exposure -= kExposureStep, c.redraw = true;
  if (k == SDLK_RIGHTBRACKET) c.exposure += kExposureStep, c.redraw = true;
  if (k == SDLK_PLUS || k == SDLK_EQUALS || k == SDLK_KP_PLUS)
    camera.ry = zoom_ry(camera.ry, 1 / kZoomStep);
  if (k == SDLK_MINUS || k == SDLK_KP_MINUS) camera.ry = zoom_ry(camera.ry, kZoomStep);
}

void on_event(const SDL_Event& e, ViewSession& s, Controls& c, CameraSpec& camera) {
  switch (e.type) {
    case SDL_QUIT:
      c.quit = true;
      break;
    case SDL_KEYDOWN:
      if (!e.key.repeat) on_key(e.key, s, c, camera);
      break;
    case SDL_MOUSEBUTTONDOWN:
      if (e.button.button == SDL_BUTTON_LEFT) c.drag = c.left_orbits ? Drag::kOrbit : Drag::kLook;
      if (e.button.button == SDL_BUTTON_RIGHT) c.drag = Drag::kOrbit;
      if (c.drag == Drag::kOrbit) c.pivot = orbit_pivot(s);
      break;
    case SDL_MOUSEBUTTONUP:
      c.drag = Drag::kNone;
      break;
    case SDL_MOUSEMOTION: {
      if (c.drag == Drag::kNone) break;
      // Looking: a drag across the window turns the view by its field of view, so the scene
      // follows the cursor. Right and up turn right and up (yaw and pitch count left and up).
      double h = c.window_height;
      if (c.drag == Drag::kLook) {
        double k = vertical_fov_degrees(camera.ry) / h;
        camera = fly_look(camera, -e.motion.xrel * k, -e.motion.yrel * k, s.world_up());
      } else {
        double k = kOrbitDegreesPerHeight / h;
        camera = orbit(camera, c.pivot, -e.motion.xrel * k, -e.motion.yrel * k, s.world_up());
      }
      break;
    }
    case SDL_MOUSEWHEEL:
      if (e.wheel.y != 0)
        camera.ry = zoom_ry(camera.ry, std::pow(kZoomStep, e.wheel.y > 0 ? -1.0 : 1.0));
      break;
    case SDL_WINDOWEVENT:
      if (e.window.event == SDL_WINDOWEVENT_EXPOSED ||
          e.window.event == SDL_WINDOWEVENT_SIZE_CHANGED)
        c.redraw = true;
      break;
  }
}

// The arrow keys (forward, back, left, right) and Page Up / Page Down (up, down) while held,
// in scene units for `seconds` of flight.
bool fly_keys(const ViewSession& s, double seconds, CameraSpec& camera) {
  const Uint8* held = SDL_GetKeyboardState(nullptr);
  SDL_Keymod mod = SDL_GetModState();
  if (mod & KMOD_CTRL) return false;  // Ctrl+S and Ctrl+Q are commands, not moves
  auto axis = [&](SDL_Scancode plus, SDL_Scancode minus) {
    return double(held[plus]) - double(held[minus]);
  };
  glm::dvec3 dir(axis(SDL_SCANCODE_RIGHT, SDL_SCANCODE_LEFT),
                 axis(SDL_SCANCODE_PAGEUP, SDL_SCANCODE_PAGEDOWN),
                 axis(SDL_SCANCODE_UP, SDL_SCANCODE_DOWN));
  if (dir == glm::dvec3(0, 0, 0)) return false;
  double speed = kSpeedPerSize * s.scene_size() * (mod & KMOD_SHIFT ? 4 : 1);
  camera = fly_move(camera, dir * (speed * seconds), s.world_up());
  return true;
}

// Waits up to `ms` for an event, polling. Not SDL_WaitEventTimeout: SDL 2.26 on X11 wakes that
// wait with an XSendEvent to the window over a second X connection, sent even for the events
// its own thread queues. The server may handle one sent just before Q after the window is
// destroyed on the first connection: BadWindow, and Xlib's default handler exits with status 1
// (the Xvfb test saw it in about 1 run of 10). A poll every 5 ms costs nothing measurable.
bool idle_until_event(SDL_Event& e, int ms) {
  for (int waited = 0; waited < ms; waited += 5) {
    if (SDL_PollEvent(&e)) return true;
    SDL_Delay(5);
  }
  return SDL_PollEvent(&e) != 0;
}

}  // namespace

int run_view_window(ViewSession& s, const std::string& name) {
  Sdl sdl;
  // SDL 2.26 tries Wayland before X11, and libwayland prints "error: XDG_RUNTIME_DIR not set
  // in the environment." when it cannot look for a compositor. With an X display and no Wayland
  // one named, X11 is asked for first; SDL_VIDEODRIVER in the environment still wins.
  if (std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY"))
    SDL_SetHintWithPriority(SDL_HINT_VIDEODRIVER, "x11", SDL_HINT_DEFAULT);
  if (SDL_Init(SDL_INIT_VIDEO) != 0) {
    const char* display = std::getenv("DISPLAY");
    std::fprintf(stderr, "raylane: view needs a display: %s (DISPLAY=%s)\n", SDL_GetError(),
                 display ? display : "");
    return kExitUsage;
  }
  // Failing X11 and Wayland, SDL 2.26 settles for its offscreen driver: a window nobody sees.
  // That is no display, unless SDL_VIDEODRIVER asked for it.
  std::string driver = SDL_GetCurrentVideoDriver() ? SDL_GetCurrentVideoDriver() : "";
  if ((driver == "offscreen" || driver == "dummy") && !std::getenv("SDL_VIDEODRIVER")) {
    const char* display = std::getenv("DISPLAY");
    std::fprintf(stderr,
                 "raylane: view needs a display, and none could be opened (DISPLAY=%s; SDL "
                 "fell back to its %s driver)\n",
                 display ? display : "", driver.c_str());
    return kExitUsage;
  }
  // The window is a plain software surface (X11's own framebuffer). Left to itself, SDL 2 on
  // Linux draws the surface through an OpenGL renderer, whose set-up destroys the X window and
  // makes a new one at the first frame (SDL_RecreateWindow): a window manager or xdotool that
  // found the first one loses it. A blit of one image a frame needs no GPU. The environment's
  // SDL_FRAMEBUFFER_ACCELERATION still wins over this default.
  SDL_SetHintWithPriority(SDL_HINT_FRAMEBUFFER_ACCELERATION, "0", SDL_HINT_DEFAULT);
  // A screen larger than the largest window is rendered at its own size and shown scaled.
  auto [window_w, window_h] = fitted_screen(s.width(), s.height());
  sdl.window = SDL_CreateWindow(cat("raylane view: ", name).c_str(), SDL_WINDOWPOS_UNDEFINED,
                                SDL_WINDOWPOS_UNDEFINED, int(window_w), int(window_h), 0);
  if (!sdl.window) {
    std::fprintf(stderr, "raylane: cannot open the view's window: %s\n", SDL_GetError());
    return kExitUsage;
  }
  std::fprintf(
      stderr, "raylane view: %s, %ux%u%s\n%s", name.c_str(), s.width(), s.height(),
      window_w == s.width() ? "" : cat(", shown in a ", window_w, "x", window_h, " window").c_str(),
      kViewKeys);
  Controls c;
  c.window_height = window_h;
  FrameRate frames;
  auto last_frame = Clock::now(), last_move = Clock::now() - std::chrono::seconds(1);
  bool worked = true;
  while (!c.quit) {
    CameraSpec camera = s.camera();
    SDL_Event e;
    // Nothing to render and nothing held: sleep until an event (or the file watch is due).
    if (!worked && c.drag == Drag::kNone && !c.redraw && idle_until_event(e, 250))
      on_event(e, s, c, camera);
    while (SDL_PollEvent(&e))
      on_event(e, s, c, camera);
    auto now = Clock::now();
    auto frame_start = now;
    double dt = std::min(kLongestStep, std::chrono::duration<double>(now - last_frame).count());
    last_frame = now;
    fly_keys(s, dt, camera);
    if (s.set_camera(camera)) last_move = now;
    if (s.inputs_changed() && s.reload()) c.redraw = true;
    bool moving = std::chrono::duration<double>(now - last_move).count() < kStillSeconds;
    worked = s.step(moving);
    if (worked || c.redraw) {
      present(sdl.window, s.display_image(), c.exposure);
      if (worked) frames.frame(std::chrono::duration<double>(Clock::now() - frame_start).count());
      SDL_SetWindowTitle(sdl.window, title(s, name, c, frames).c_str());
      c.redraw = false;
    }
  }
  return kExitOk;
}

}  // namespace raylane::cli
