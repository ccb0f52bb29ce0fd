#include "exr_extras.h"

#include <algorithm>

#include "raylane/core/input_file.h"
#include "raylane/core/strings.h"

namespace raylane::cli {

namespace {

// The channels without a layer that the colour does not take: R, G, B are the colour (or Y
// alone, read as grey).
std::vector<std::string> unlayered_left_out(const ExrInfo& info) {
  std::vector<std::string> out;
  for (const std::string& c : info.channels) {
    if (c.find('.') != std::string::npos) continue;
    bool colour = info.has_rgb ? (c == "R" || c == "G" || c == "B") : c == "Y";
    if (!colour) out.push_back(c);
  }
  return out;
}

}  // namespace

Result<ExrExtras> read_exr_extras(const std::string& path) {
  auto bytes = read_input_file(path, uint64_t(4) << 30, "the image");
  if (!bytes) return Error{bytes.error()};
  auto info = probe_exr(*bytes);
  if (!info) return Error{cat("cannot read ", quote_path(path), ": ", info.error())};
  ExrExtras out;
  for (const std::string& line : info->metadata)
    if (line.rfind("software=", 0) != 0) out.metadata.push_back(line);
  for (const std::string& c : unlayered_left_out(*info))
    out.not_kept.push_back(cat("channel ", c, " (only R, G, B and layers are written)"));
  for (const std::string& name : info->layers) {
    if (name.empty()) continue;
    auto layer = decode_exr_layer(*bytes, name);
    if (!layer) {
      out.not_kept.push_back(cat("layer ", name, " (", layer.error(), ")"));
      continue;
    }
    out.layers.push_back(std::move(*layer));
  }
  return out;
}

}  // namespace raylane::cli
