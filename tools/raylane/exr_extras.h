// What `raylane convert` carries from an EXR into an EXR beside the colour: every layer of
// half or float channels (LAYER.CHANNEL, as `render --aov` writes them) and the header's string
// attributes (RAYLANE_SPP, RAYLANE_SEED, ...), so that converting EXR to EXR (to --half, or to
// re-compress) loses nothing a render wrote.
#pragma once

#include <string>
#include <vector>

#include "raylane/core/error.h"
#include "raylane/image/exr.h"

namespace raylane::cli {

struct ExrExtras {
  std::vector<ExrLayer> layers;       // in the file's order
  std::vector<std::string> metadata;  // KEY=value; not "software", which the writer sets
  std::vector<std::string> not_kept;  // what the output cannot hold, and why: for warnings
};

// Errors only when the file cannot be read or decoded at all; a layer that cannot be kept
// (integer or subsampled channels, a channel beside R, G, B without a layer) is named in
// not_kept instead.
Result<ExrExtras> read_exr_extras(const std::string& path);

}  // namespace raylane::cli
