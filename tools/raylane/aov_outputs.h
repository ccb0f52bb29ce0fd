// Where `raylane render --aov` puts the AOVs (render/film/aov.h): layers of an EXR output, PFM
// files beside the other outputs.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "raylane/image/exr.h"
#include "raylane/render/film/film.h"

namespace raylane::cli {

bool is_exr(const std::string& path);

// STEM.NAME.pfm beside each output that is not EXR for each AOV, once per stem.
std::vector<std::pair<std::string, Aov>> aov_siblings(const std::vector<std::string>& outputs,
                                                      AovSet set);

// The film's AOVs as EXR layers: albedo.R/G/B, normal.X/Y/Z, depth.Z, position.X/Y/Z.
std::vector<ExrLayer> exr_layers_of(const Film& film);

}  // namespace raylane::cli
