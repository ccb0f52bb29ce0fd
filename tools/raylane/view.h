// `raylane view`: the interactive viewer. view_command.cpp reads the options and the scene;
// view_loop.cpp (built only with SDL2) runs the window.
#pragma once

#include "raylane/scene/parser.h"
#include "view_session.h"

namespace raylane::cli {

// The keys and the mouse, as `raylane view --help` and the viewer's start print them.
inline constexpr const char* kViewKeys =
    "keys (the window must have the focus):\n"
    "  arrow keys       fly forward, back, left, right; Page Up / Page Down: up, down\n"
    "                   (world up); hold Shift to go 4x faster\n"
    "  left drag        look around (or orbit, after O)\n"
    "  right drag       orbit about the surface point at the centre of the view\n"
    "  O                left drag: switch between look and orbit\n"
    "  wheel, + -       field of view\n"
    "  [ ]              exposure down, up by half a stop\n"
    "  1..8             path, lit, normal, albedo, depth, uv, id, position; M: the next one\n"
    "  V                print the screen and camera lines (scene syntax) on stdout\n"
    "  S (P, Ctrl+S)    save view-NNNN.hdr and view-NNNN.png here (never over a file)\n"
    "  R                reload the scene (also when a file it reads changes)\n"
    "  Q, Esc (Ctrl+Q)  quit\n";

// Runs the window until the user quits. Returns the exit status: kExitUsage without a display.
int run_view_window(ViewSession& session, const std::string& scene_name);

}  // namespace raylane::cli
