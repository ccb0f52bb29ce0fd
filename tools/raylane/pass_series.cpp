#include "pass_series.h"

#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "aov_outputs.h"
#include "args.h"
#include "raylane/core/strings.h"
#include "raylane/image/write_fallback.h"
#include "raylane/render/raycast.h"
#include "render_request.h"

namespace raylane::cli {

Result<std::vector<int>> parse_save_at(const std::string& list, int max_spp) {
  std::vector<int> at;
  std::size_t begin = 0;
  while (true) {
    std::size_t end = list.find(',', begin);
    std::string item = list.substr(begin, end == std::string::npos ? end : end - begin);
    if (item.empty())
      return Error{
          cat("--save-at takes pass counts separated by commas (1,4,16), found ", in_quotes(list))};
    auto n = parse_int_option("save-at", item, 1, max_spp);
    if (!n) return Error{n.error()};
    at.push_back(int(*n));
    if (end == std::string::npos) break;
    begin = end + 1;
  }
  std::sort(at.begin(), at.end());
  at.erase(std::unique(at.begin(), at.end()), at.end());
  return at;
}

Status set_save_at(RenderRequest& r, const std::string& list) {
  auto at = parse_save_at(list, kMaxSpp);
  if (!at) return Error{at.error()};
  r.save_at = std::move(*at);
  return ok_status();
}

Status check_save_at(const RenderRequest& r) {
  if (r.save_at.empty() || !r.path || r.save_at.back() <= r.path_settings.spp) return ok_status();
  return Error{cat("--save-at ", r.save_at.back(), " is beyond --spp ", r.path_settings.spp,
                   ": the render stops before that pass")};
}

bool is_pass_pattern(const std::string& output) {
  return output.find(kPassPlaceholder) != std::string::npos;
}

std::string with_passes(const std::string& output, int passes) {
  std::string out = output;
  const std::string n = std::to_string(passes);
  for (std::size_t at = out.find(kPassPlaceholder); at != std::string::npos;
       at = out.find(kPassPlaceholder, at + n.size()))
    out.replace(at, kPassPlaceholder.size(), n);
  return out;
}

namespace {

// The first brace of `name` that is not part of a {pass}, with what follows it up to the
// closing brace (or 8 bytes): "{pas}", "{", "}". Empty when every brace is a placeholder's.
std::string stray_brace(const std::string& name) {
  for (std::size_t i = 0; i < name.size(); ++i) {
    if (name.compare(i, kPassPlaceholder.size(), kPassPlaceholder) == 0) {
      i += kPassPlaceholder.size() - 1;
      continue;
    }
    if (name[i] == '{' || name[i] == '}') {
      const std::size_t close = name.find('}', i + 1);
      return name.substr(
          i, name[i] == '{' && close != std::string::npos && close - i < 16 ? close - i + 1 : 1);
    }
  }
  return "";
}

}  // namespace

Status check_pass_patterns(const RenderRequest& r) {
  for (const std::string& out : r.outputs) {
    const std::filesystem::path p(out);
    if (std::string bad = stray_brace(p.filename().string()); !bad.empty())
      return Error{cat("expected the placeholder {pass} in the output name ", quote_path(out),
                       ", found ", in_quotes(bad), " (braces name nothing else)")};
    if (p.parent_path().string().find_first_of("{}") != std::string::npos)
      return Error{cat("expected {pass} in the file name of the output ", quote_path(out),
                       ", found braces in its folder (one folder holds the whole series)")};
    if (is_pass_pattern(out) && !r.path)
      return Error{cat("the output ", quote_path(out), " holds {pass}, the pass count of a path ",
                       "render; --mode ", raycast_mode_name(r.mode), " renders no passes")};
  }
  return ok_status();
}

std::vector<std::string> final_outputs(const RenderRequest& r, int passes) {
  std::vector<std::string> out;
  const bool in_series = std::binary_search(r.save_at.begin(), r.save_at.end(), passes);
  for (const std::string& o : r.outputs) {
    if (!is_pass_pattern(o)) {
      out.push_back(o);
    } else if (!in_series) {
      out.push_back(with_passes(o, passes));
    }
  }
  return out;
}

std::string series_path(const std::string& output, int passes) {
  if (is_pass_pattern(output)) return with_passes(output, passes);
  std::filesystem::path p(output);
  std::string name = cat(p.stem().string(), ".", passes, p.extension().string());
  return (p.parent_path() / name).string();
}

namespace {

std::string comma_list(const std::vector<int>& v) {
  std::string out;
  for (int n : v)
    out += (out.empty() ? "" : ",") + std::to_string(n);
  return out;
}

std::vector<std::string> outputs_at(const RenderRequest& r, int passes) {
  std::vector<std::string> out;
  for (const std::string& o : r.outputs)
    out.push_back(series_path(o, passes));
  return out;
}

}  // namespace

std::vector<std::string> series_outputs(const RenderRequest& r) {
  std::vector<std::string> all;
  for (int n : r.save_at) {
    std::vector<std::string> colour = outputs_at(r, n);
    for (const auto& [path, aov] : aov_siblings(colour, r.path_settings.aovs))
      colour.push_back(path);
    all.insert(all.end(), colour.begin(), colour.end());
  }
  return all;
}

void PassSeries::start(const Film& film) {
  if (r_.save_at.empty() || film.passes == 0) return;
  std::vector<int> past;
  for (int n : r_.save_at)
    if (n < film.passes) past.push_back(n);
  if (!past.empty() && cluster_.root() && !r_.quiet)
    std::fprintf(stderr,
                 "raylane: warning: --save-at %s: the --resume film already holds %d passes; "
                 "those images are not written\n",
                 comma_list(past).c_str(), film.passes);
  if (std::binary_search(r_.save_at.begin(), r_.save_at.end(), film.passes))
    after_pass(film.passes, film);
}

void PassSeries::after_pass(int done, const Film& film) {
  if (!std::binary_search(r_.save_at.begin(), r_.save_at.end(), done)) return;
  if (!cluster_.distributed()) return write(film, done);
  Film whole = film;  // this process's share; rank 0's copy receives the others'
  cluster_.assemble(whole);
  if (cluster_.root()) write(whole, done);
}

void PassSeries::finish(int passes_done) const {
  std::vector<int> missed;
  for (int n : r_.save_at)
    if (n > passes_done) missed.push_back(n);
  if (!missed.empty() && cluster_.root() && !r_.quiet)
    std::fprintf(stderr, "raylane: warning: --save-at %s: the render stopped after %d passes\n",
                 comma_list(missed).c_str(), passes_done);
}

double process_cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  auto seconds = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
  return seconds(u.ru_utime) + seconds(u.ru_stime);
}

// The files `raylane render --spp N` writes: the same options, RAYLANE_SPP=N.
void PassSeries::write(const Film& film, int passes) {
  SeriesSave save;
  save.spp = passes;
  const double cpu = process_cpu_seconds();
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  save.cpu_seconds = cpu - writing_cpu_;
  save.seconds = wall - writing_seconds_;
  WriteOptions wopts;
  wopts.exposure = r_.exposure;
  wopts.exr_half = r_.exr_half;
  wopts.metadata.push_back("RAYLANE_MODE=path");
  wopts.metadata.push_back(cat("RAYLANE_SPP=", passes));
  for (std::string& line : path_metadata(r_.path_settings))
    wopts.metadata.push_back(std::move(line));
  save.outputs = write_film_outputs(outputs_at(r_, passes), film, wopts, failed_);
  std::fflush(stdout);
  saves_.push_back(std::move(save));
  writing_cpu_ += process_cpu_seconds() - cpu;
  writing_seconds_ +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count() - wall;
}

std::vector<std::string> write_film_outputs(const std::vector<std::string>& colour,
                                            const Film& film, const WriteOptions& options,
                                            bool& failed) {
  std::vector<std::string> written;
  auto keep = [&](std::optional<std::string> path) {
    if (path) written.push_back(std::move(*path));
  };
  {
    const Image image = film.image();
    for (const std::string& out : colour) {
      if (!is_exr(out) || film.aovs.empty()) {
        keep(write_render_output(out, image, options, failed));
        continue;
      }
      WriteOptions with_layers = options;
      with_layers.exr_layers = exr_layers_of(film);
      keep(write_render_output(out, image, with_layers, failed));
    }
  }
  for (const auto& [out, aov] : aov_siblings(colour, film.aovs))
    keep(write_render_output(out, film.aov_image(aov), options, failed));
  return written;
}

namespace {
std::vector<std::string>& written_so_far() {
  static std::vector<std::string> files;
  return files;
}
}  // namespace

const std::vector<std::string>& files_written() {
  return written_so_far();
}

std::optional<std::string> write_render_output(const std::string& out, const Image& image,
                                               const WriteOptions& options, bool& failed) {
  auto saved = write_image_or_fallback(out, image, options);
  if (!saved) {
    std::fprintf(stderr, "raylane: cannot write %s: %s\n", out.c_str(), saved.error().c_str());
    failed = true;
    return std::nullopt;
  }
  if (saved->is_fallback) {
    std::fprintf(stderr, "raylane: cannot write %s: %s; the image is saved as %s\n", out.c_str(),
                 saved->first_error.c_str(), saved->path.c_str());
    failed = true;
  }
  std::printf("%s\n", saved->path.c_str());
  written_so_far().push_back(saved->path);
  return saved->path;
}

}  // namespace raylane::cli
