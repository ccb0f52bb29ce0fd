// What a long render tells its user: a progress bar with elapsed time and ETA on a terminal,
// an occasional plain line otherwise (logs, pipes), nothing with --quiet.
#pragma once

#include <atomic>
#include <chrono>
#include <string>

#include "raylane/render/path.h"

namespace raylane::cli {

// `--stats`: thread-seconds per phase of the path tracer's loop, against the threads' time.
void print_phases(const PathStats& s, double seconds, int threads);

class Progress {
 public:
  // total_passes: the requested spp; time_limit: seconds (0 = none), which caps the ETA.
  Progress(int total_passes, double time_limit, bool quiet);
  void update(int passes_done);  // called after each pass, from the rendering thread
  void finish();                 // ends the bar's line
  double elapsed() const;

 private:
  // The requested spp, or "…" for a render that only a time budget ends.
  std::string total_text() const {
    return time_limit_ > 0 && total_ >= (1 << 24) ? "…" : std::to_string(total_);
  }
  int total_;
  double time_limit_;
  bool quiet_, tty_;
  double last_report_ = 0;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_;
};

// SIGINT handling for renders: the first Ctrl-C sets the flag (the renderer finishes the
// passes in flight and the image converged so far is written); a second exits at once with
// status 130 without writing.
// SIGTERM and SIGUSR1 do the same on one process; started by a launcher, they only ask for the
// stop after the pass.
void install_interrupt_handler(bool under_launcher = false);
bool interrupted();

}  // namespace raylane::cli
