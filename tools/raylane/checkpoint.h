// `--checkpoint FILE` and `--resume FILE` of path renders: the film is saved every
// `--checkpoint-every` seconds and whenever the render stops (done, time budget, Ctrl-C), and a
// saved film continues to the image an uninterrupted run gives.
#pragma once

#include <chrono>
#include <optional>
#include <string>

#include "args.h"
#include "raylane/render/film/film.h"

namespace raylane::cli {

struct CheckpointOptions {
  std::optional<std::string> checkpoint, resume;
  double every = 60;  // seconds between saves
};

// The film to render into: empty, or the --resume film once it is known to belong to this
// scene and these settings.
Result<Film> starting_film(const CheckpointOptions& c, const Scene& scene,
                           const PathSettings& settings);

// Saves the film to --checkpoint after a pass when `every` seconds have passed, or always
// with `final`. Prints failures; a failed checkpoint never stops the render.
class Checkpointer {
 public:
  explicit Checkpointer(const CheckpointOptions& c) : options_(c) {}
  bool due() const;             // a --checkpoint is asked for and `every` seconds have passed
  void save(const Film& film);  // saves now (if a --checkpoint is asked for)

 private:
  CheckpointOptions options_;
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

// A path render whose files could not all be written keeps its film: saved, identified so that
// --resume takes it, as `raylane-rescue-<stem>-<pid>-<n>.film` in the folder of `output`, else
// the working directory, else the system's temporary folder. The path saved, or an error
// naming every place tried.
Result<std::string> save_rescue_film(Film& film, const Scene& scene, const PathSettings& settings,
                                     const std::string& output);

}  // namespace raylane::cli
