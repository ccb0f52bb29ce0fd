// `raylane info FILM`: what a saved film (--checkpoint) holds, so a user can tell which render
// it continues: its size, passes (spp), seed, integrator, sampler, shading and AOVs.
#pragma once

#include <string>

namespace raylane::cli {

// Whether the file starts with a film's magic (either format).
bool is_film_file(const std::string& path);
// Prints the film's header on stdout; returns the exit status (2 for a film that does not load).
int info_film(const std::string& path);

}  // namespace raylane::cli
