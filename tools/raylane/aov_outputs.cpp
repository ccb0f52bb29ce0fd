#include "aov_outputs.h"

#include <algorithm>
#include <filesystem>

#include "raylane/core/strings.h"
#include "raylane/image/write_image.h"

namespace raylane::cli {

bool is_exr(const std::string& path) {
  auto f = format_from_path(path);
  return f && *f == ImageFormat::kExr;
}

// STEM.NAME.pfm beside each output for each AOV, once per stem (out.hdr and out.png share
// theirs): PFM keeps negative normals and positions, and is what denoisers read. An EXR output
// holds its AOVs as layers instead (exr_layers_of).
std::vector<std::pair<std::string, Aov>> aov_siblings(const std::vector<std::string>& outputs,
                                                      AovSet set) {
  std::vector<std::pair<std::string, Aov>> out;
  std::vector<std::string> stems;
  for (const std::string& o : outputs) {
    if (is_exr(o)) continue;
    std::string stem = std::filesystem::path(o).replace_extension().string();
    if (std::find(stems.begin(), stems.end(), stem) != stems.end()) continue;
    stems.push_back(stem);
    for (std::size_t k = 0; k < kAovCount; ++k)
      if (set.has(Aov(k))) out.emplace_back(cat(stem, ".", kAovNames.name(Aov(k)), ".pfm"), Aov(k));
  }
  return out;
}

// The film's AOVs as EXR layers: albedo.R/G/B, normal.X/Y/Z, depth.Z, position.X/Y/Z.
std::vector<ExrLayer> exr_layers_of(const Film& film) {
  std::vector<ExrLayer> layers;
  for (std::size_t k = 0; k < kAovCount; ++k) {
    const Aov aov = Aov(k);
    if (!film.aovs.has(aov)) continue;
    ExrLayer layer{std::string(kAovNames.name(aov)), {}, {}};
    if (aov == Aov::kAlbedo)
      layer.channels = {"R", "G", "B"};
    else if (aov == Aov::kDepth)
      layer.channels = {"Z"};
    else
      layer.channels = {"X", "Y", "Z"};
    const Image img = film.aov_image(aov);
    const std::size_t n = layer.channels.size();
    layer.data.resize(std::size_t(img.width) * img.height * n);
    for (std::size_t p = 0; p < std::size_t(img.width) * img.height; ++p)
      for (std::size_t c = 0; c < n; ++c)
        layer.data[p * n + c] = img.rgb[p * 3 + c];
    layers.push_back(std::move(layer));
  }
  return layers;
}

}  // namespace raylane::cli
