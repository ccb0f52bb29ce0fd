#include "checkpoint.h"

#include <cstdio>
#include <filesystem>

#include "raylane/core/atomic_file.h"
#include "raylane/core/strings.h"
#include "raylane/image/write_fallback.h"

namespace raylane::cli {

Result<Film> starting_film(const CheckpointOptions& c, const Scene& scene,
                           const PathSettings& settings) {
  if (!c.resume) {
    Film film;  // a film to be saved carries what its samples depend on; others need not
    if (c.checkpoint) identify_film(film, scene, settings);
    film.region = settings.region;
    return film;
  }
  auto film = load_film(*c.resume);
  if (!film) return Error{film.error()};
  if (film->width != scene.width || film->height != scene.height)
    return Error{cat(*c.resume, ": expected a ", scene.width, "x", scene.height,
                     " film for this scene, found ", film->width, "x", film->height)};
  if (film->fingerprint != film_fingerprint(scene, settings)) {
    std::string what = origin_difference(film->origin, film_origin(scene, settings));
    if (what.empty()) what = "another scene or other --seed, --integrator or --max-depth";
    return Error{
        cat(*c.resume, ": the film was rendered with ", what, "; resume with the same ones")};
  }
  if (film->region != settings.region) {
    auto text = [](const std::optional<PixelRegion>& r) {
      return r ? cat("--region ", region_text(*r)) : std::string("the whole image");
    };
    return Error{cat(*c.resume, ": the film holds ", text(film->region), ", this run asks for ",
                     text(settings.region), "; resume with ",
                     film->region ? text(film->region) : "no --region")};
  }
  if (film->aovs != settings.aovs)
    return Error{cat(*c.resume, ": the film sums the AOVs (", aov_list_text(film->aovs),
                     "), this run asks for (", aov_list_text(settings.aovs),
                     "); resume with the same --aov")};
  return film;
}

bool Checkpointer::due() const {
  if (!options_.checkpoint) return false;
  auto now = std::chrono::steady_clock::now();
  return std::chrono::duration<double>(now - last_).count() >= options_.every;
}

void Checkpointer::save(const Film& film) {
  if (!options_.checkpoint) return;
  last_ = std::chrono::steady_clock::now();
  if (Status s = save_film(*options_.checkpoint, film); !s)
    std::fprintf(stderr, "raylane: checkpoint not saved: %s\n", s.error().c_str());
}

Result<std::string> save_rescue_film(Film& film, const Scene& scene, const PathSettings& settings,
                                     const std::string& output) {
  identify_film(film, scene, settings);
  const std::filesystem::path out(output);
  std::vector<std::string> dirs = default_fallback_dirs();
  dirs.insert(dirs.begin(), out.has_parent_path() ? out.parent_path().string() : ".");
  std::string stem = out.stem().string();
  if (stem.empty()) stem = "render";
  std::string errors;
  for (const std::string& dir : dirs) {
    std::string path = fresh_rescue_name(dir, stem, ".film");
    if (path.empty()) continue;
    Status s = save_film(path, film);
    if (s) return path;
    errors += cat(errors.empty() ? "" : "; ", path, ": ", s.error());
  }
  return Error{cat("the film could not be saved anywhere (", errors, ")")};
}

}  // namespace raylane::cli
