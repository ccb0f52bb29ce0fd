#include "film_info.h"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "commands.h"
#include "raylane/core/strings.h"
#include "raylane/render/film/film.h"

namespace raylane::cli {

namespace {

// A name from a film's stored enum value, which a damaged film may hold out of range.
template <class E, std::size_t N>
std::string stored_name(const EnumNames<E, N>& names, int32_t value) {
  if (value < 0 || std::size_t(value) >= N) return cat("unknown (", value, ")");
  return std::string(names.name(E(value)));
}

std::string aov_list(AovSet set) {
  std::string out;
  for (std::size_t k = 0; k < kAovCount; ++k)
    if (set.has(Aov(k))) out += cat(out.empty() ? "" : ",", kAovNames.name(Aov(k)));
  return out.empty() ? "none" : out;
}

}  // namespace

bool is_film_file(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return false;  // a FIFO would block the read
  std::ifstream in(path, std::ios::binary);
  char head[7] = {};
  return in.read(head, 7) && std::string_view(head, 6) == "RLFILM" &&
         (head[6] >= '1' && head[6] <= '3');
}

int info_film(const std::string& path) {
  auto film = load_film(path);
  if (!film) {
    std::fprintf(stderr, "raylane: %s\n", film.error().c_str());
    return kExitUsage;
  }
  std::printf("film: %s\n", quote_path(path).c_str());
  std::printf("size: %u x %u\n", film->width, film->height);
  std::printf("spp: %d\n", film->passes);
  const FilmOrigin& o = film->origin;
  if (o.known) {
    std::printf("seed: %llu\n", (unsigned long long)o.seed);
    std::printf("integrator: %s\n", stored_name(kIntegratorNames, o.integrator).c_str());
    std::printf("sampler: %s\n", stored_name(kSamplerNames, o.sampler).c_str());
    std::printf("shading: %s\n", stored_name(kShadingNames, o.shading).c_str());
    std::printf("max depth: %d (roulette from bounce %d)\n", o.max_depth, o.rr_depth);
  } else {
    std::printf(
        "origin: not recorded (a film of the first format: seed, integrator and sampler "
        "unknown)\n");
  }
  std::printf("aovs: %s\n", aov_list(film->aovs).c_str());
  std::string region = film->region ? cat(" --region ", region_text(*film->region)) : "";
  if (film->region) std::printf("region: %s\n", region_text(*film->region).c_str());
  std::printf("continue with: raylane render SCENE --resume %s%s --spp N (N > %d)\n",
              quote_path(path).c_str(), region.c_str(), film->passes);
  return kExitOk;
}

}  // namespace raylane::cli
