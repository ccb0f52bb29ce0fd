#include "raylane/render/film/film.h"

#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "raylane/core/atomic_file.h"
#include "raylane/core/input_file.h"
#include "raylane/core/strings.h"

namespace raylane {

namespace {

static_assert(std::endian::native == std::endian::little, "film files are little endian");

constexpr char kMagic1[8] = {'R', 'L', 'F', 'I', 'L', 'M', '1', '\0'};
constexpr char kMagic2[8] = {'R', 'L', 'F', 'I', 'L', 'M', '2', '\0'};
constexpr char kMagic3[8] = {'R', 'L', 'F', 'I', 'L', 'M', '3', '\0'};  // a region's film
constexpr std::size_t kHeader1 = 32, kHeader2 = 64;
constexpr char kAovMagic[4] = {'A', 'O', 'V', '1'};
constexpr std::size_t kAovHeader = 8;                   // the magic and the set's bits
constexpr char kRegionMagic[4] = {'R', 'G', 'N', '1'};  // after whole-image sums (read only)
constexpr std::size_t kRegionBytes = 20;                // the magic and x0, y0, x1, y1
constexpr std::size_t kCorners = 16;  // x0, y0, x1, y1 after a third-format header

// The header of either format, read into a film (sums not yet read).
Film read_header(const char* head, bool second_format) {
  Film f;
  uint32_t words[4];
  std::memcpy(words, head + 8, sizeof words);
  std::memcpy(&f.fingerprint, head + 24, 8);
  f.width = words[0], f.height = words[1], f.passes = int(words[2]);
  if (second_format) {
    f.origin.known = true;
    f.origin.integrator = int32_t(words[3]);
    std::memcpy(&f.origin.scene, head + 32, 8);
    std::memcpy(&f.origin.seed, head + 40, 8);
    std::memcpy(&f.origin.max_depth, head + 48, 4);
    std::memcpy(&f.origin.rr_depth, head + 52, 4);
    std::memcpy(&f.origin.sampler, head + 56, 4);  // 0 (MT19937) in films from before samplers
    std::memcpy(&f.origin.shading, head + 60, 4);  // 0 (double) in films from before lanes
  }
  return f;
}

// The AOV part of a film file: `bytes` after the colour sums.
Status read_aovs(std::ifstream& in, const std::string& path, uint64_t bytes, uint64_t pixels,
                 Film& f) {
  char head[kAovHeader];
  if (bytes < kAovHeader)
    return Error{cat(path, ": expected AOVs after the colour sums, found ", bytes, " bytes")};
  if (!in.read(head, kAovHeader)) return Error{cat(path, ": read failed")};
  std::memcpy(&f.aovs.bits, head + 4, 4);
  if (std::memcmp(head, kAovMagic, 4) != 0 || f.aovs.empty() || f.aovs.bits >> kAovCount)
    return Error{cat(path, ": expected 'AOV1' and a set of AOVs after the colour sums, found ",
                     in_quotes(std::string_view(head, 4)), " and bits ", f.aovs.bits)};
  const uint64_t expected = kAovHeader + pixels * uint64_t(f.aovs.channels()) * 8;
  if (bytes != expected)
    return Error{cat(path, ": its AOVs (", aov_list_text(f.aovs), ") take ", expected,
                     " bytes after the colour sums, the file has ", bytes)};
  f.aov_sum.resize(pixels * std::size_t(f.aovs.channels()));
  if (!in.read(reinterpret_cast<char*>(f.aov_sum.data()),
               std::streamsize(f.aov_sum.size() * sizeof(double))))
    return Error{cat(path, ": read failed")};
  return ok_status();
}

Status read_corners(const char* corners, const std::string& path, Film& f);

// The region part of a film file of the second format, if the next bytes (of `bytes` left) are one;
// `bytes` then counts what is left after it.
Status read_region(std::ifstream& in, const std::string& path, uint64_t& bytes, Film& f) {
  if (bytes < kRegionBytes) return ok_status();
  char part[kRegionBytes];
  if (!in.read(part, 4)) return Error{cat(path, ": read failed")};
  if (std::memcmp(part, kRegionMagic, 4) != 0) {
    in.seekg(-4, std::ios::cur);
    return ok_status();
  }
  if (!in.read(part + 4, kRegionBytes - 4)) return Error{cat(path, ": read failed")};
  if (Status s = read_corners(part + 4, path, f); !s) return s;
  bytes -= kRegionBytes;
  return ok_status();
}

// A region's corners (x0, y0, x1, y1) into the film, checked against its image.
Status read_corners(const char* corners, const std::string& path, Film& f) {
  PixelRegion r;
  std::memcpy(&r.x0, corners, 4), std::memcpy(&r.y0, corners + 4, 4);
  std::memcpy(&r.x1, corners + 8, 4), std::memcpy(&r.y1, corners + 12, 4);
  if (Status s = check_region(r, f.width, f.height); !s)
    return Error{cat(path, ": the film's region ", s.error(), ": the film is damaged")};
  f.region = r;
  return ok_status();
}

// Whole-image sums (`channels` per pixel) cut to the film's region: a region film of the
// second format summed every pixel of the image.
void keep_region_only(std::vector<double>& sums, std::size_t channels, const Film& f) {
  const PixelRegion& r = *f.region;
  std::vector<double> kept;
  kept.reserve(std::size_t(r.width()) * r.height() * channels);
  for (uint32_t y = r.y0; y < r.y1; ++y) {
    auto row = sums.begin() + std::ptrdiff_t((std::size_t(y) * f.width + r.x0) * channels);
    kept.insert(kept.end(), row, row + std::ptrdiff_t(std::size_t(r.width()) * channels));
  }
  sums = std::move(kept);
}

// FNV-1a, 64 bits (Fowler, Noll, Vo): enough to tell one scene or setting from another.
struct Hasher {
  uint64_t h = 0xcbf29ce484222325ull;
  void bytes(const void* p, std::size_t n) {
    auto* c = static_cast<const unsigned char*>(p);
    for (std::size_t i = 0; i < n; ++i)
      h = (h ^ c[i]) * 0x100000001b3ull;
  }
  template <class T>
  void value(const T& v) {
    bytes(&v, sizeof v);
  }
  template <class T>
  void column(const std::vector<T>& c) {
    value(c.size());
    bytes(c.data(), c.size() * sizeof(T));
  }
  // Texels as the float column of RGB they decode to, whatever their storage: a film saved
  // before textures were kept compactly still fits the same scene.
  void texels(const TexelImage& t) {
    value(t.texel_count() * 3);
    for (uint32_t y = 0; y < t.height; ++y)
      for (uint32_t x = 0; x < t.width; ++x) {
        glm::vec3 c = t.at(x, y);
        float rgb[3] = {c.x, c.y, c.z};
        bytes(rgb, sizeof rgb);
      }
  }
};

}  // namespace

PixelRegion Film::window() const {
  return region ? *region : PixelRegion{0, 0, width, height};
}

std::size_t Film::stored_pixels() const {
  const PixelRegion w = window();
  return std::size_t(w.width()) * w.height();
}

std::size_t Film::slot(std::size_t pixel) const {
  return region_slot(region, width, pixel);
}

void Film::clear(uint32_t image_width, uint32_t image_height) {
  width = image_width, height = image_height, passes = 0;
  sum.assign(stored_pixels() * 3, 0.0);
  aov_sum.assign(stored_pixels() * std::size_t(aovs.channels()), 0.0);
}

void keep_share(Film& film, const TileShare& share) {
  const std::size_t aov_channels = std::size_t(film.aovs.channels());
  const PixelRegion w = film.window();
  std::size_t pixel = 0;  // the stored index, in the window's row order
  for (uint32_t y = w.y0; y < w.y1; ++y)
    for (uint32_t x = w.x0; x < w.x1; ++x, ++pixel) {
      if (share.owns(tile_of_film_pixel(film.width, film.height, x, y))) continue;
      for (std::size_t k = 0; k < 3; ++k)
        film.sum[pixel * 3 + k] = 0.0;
      for (std::size_t k = 0; k < aov_channels; ++k)
        film.aov_sum[pixel * aov_channels + k] = 0.0;
    }
}

Image Film::image() const {
  const PixelRegion w = window();
  Image img(w.width(), w.height());
  double scale = passes > 0 ? 1.0 / passes : 0.0;
  for (std::size_t i = 0; i < sum.size() && i < img.rgb.size(); ++i)
    img.rgb[i] = float(sum[i] * scale);
  return img;
}

Image Film::aov_image(Aov aov) const {
  const PixelRegion w = window();
  Image img(w.width(), w.height());
  if (!aovs.has(aov)) return img;
  const double scale = passes > 0 ? 1.0 / passes : 0.0;
  const std::size_t stride = std::size_t(aovs.channels()), at = std::size_t(aovs.offset(aov));
  const int n = aov_channels(aov);
  for (std::size_t p = 0; p < stored_pixels() && (p + 1) * stride <= aov_sum.size(); ++p)
    for (int k = 0; k < 3; ++k)
      img.rgb[p * 3 + std::size_t(k)] =
          float(aov_sum[p * stride + at + std::size_t(k % n)] * scale);
  return img;
}

Image Film::screen_image() const {
  return region ? paste_region(image(), *region, width, height) : image();
}

uint64_t scene_fingerprint(const Scene& scene) {
  return film_fingerprint(scene, PathSettings{});
}

FilmOrigin film_origin(const Scene& scene, const PathSettings& settings) {
  return film_origin(scene_fingerprint(scene), settings);
}

FilmOrigin film_origin(uint64_t scene_print, const PathSettings& settings) {
  return {true,
          scene_print,
          settings.seed,
          int32_t(settings.integrator),
          settings.max_depth,
          settings.rr_depth,
          int32_t(settings.sampler),
          int32_t(settings.shading)};
}

std::string origin_difference(const FilmOrigin& film, const FilmOrigin& run) {
  if (!film.known) return "";
  std::vector<std::string> parts;
  if (film.scene != run.scene)
    parts.push_back("the scene (its shapes, materials, camera or screen)");
  if (film.seed != run.seed)
    parts.push_back(cat("--seed ", film.seed, " (this run: ", run.seed, ")"));
  if (film.integrator != run.integrator)
    parts.push_back(cat("--integrator ", integrator_name(Integrator(film.integrator)),
                        " (this run: ", integrator_name(Integrator(run.integrator)), ")"));
  if (film.max_depth != run.max_depth)
    parts.push_back(cat("--max-depth ", film.max_depth, " (this run: ", run.max_depth, ")"));
  if (film.sampler != run.sampler)
    parts.push_back(cat("--sampler ", sampler_name(Sampler(film.sampler)),
                        " (this run: ", sampler_name(Sampler(run.sampler)), ")"));
  if (film.shading != run.shading)
    parts.push_back(cat("--shading ", shading_name(Shading(film.shading)),
                        " (this run: ", shading_name(Shading(run.shading)), ")"));
  if (film.rr_depth != run.rr_depth)
    parts.push_back(cat("the roulette depth ", film.rr_depth, " (this run: ", run.rr_depth, ")"));
  std::string out;
  for (const std::string& p : parts)
    out += (out.empty() ? "" : "; ") + p;
  return out;
}

namespace {

// The scene's part of a fingerprint: every table column, material, texel and camera value (a
// pass over all of the scene's bytes: 0.3 s for a 1.31M-triangle mesh, so it is taken only for
// a film that is saved or resumed, once).
void hash_scene(Hasher& h, const Scene& scene) {
  h.value(scene.width), h.value(scene.height);
  if (scene.camera) {
    h.value(scene.camera->eye), h.value(scene.camera->ry), h.value(scene.camera->rotation);
  }
  if (scene.lens.radius > 0) h.value(scene.lens.radius), h.value(scene.lens.focus);
  for (const Material& m : scene.materials) {
    h.value(m.kd), h.value(m.ks), h.value(m.kt), h.value(m.alpha), h.value(m.ior);
    h.value(m.emission), h.value(m.is_light);
    if (m.texture >= 0) h.value(m.texture);  // only when textured: older films still fit
    if (m.microfacet != Microfacet::kPhong) h.value(m.microfacet);  // likewise
  }
  if (const auto& env = scene.environment) {
    h.value(env->scale), h.value(env->rotation), h.value(env->texels->width);
    h.value(env->texels->height), h.texels(*env->texels);
  }
  for (const Texture& t : scene.textures) {
    h.value(t.texels.width), h.value(t.texels.height);
    h.texels(t.texels);
  }
  PrimKinds::for_each([&](auto kind) {
    // Moving spheres only when there are some: films from before them still fit.
    // CSG and SDF blocks likewise, and their leaves and programs beside the rows.
    using Kind = decltype(kind);
    if constexpr (std::is_same_v<Kind, MovingSphere> || std::is_same_v<Kind, Csg> ||
                  std::is_same_v<Kind, Sdf>)
      if (scene.table<Kind>().size() == 0) return;
    // columns() hands out references for writing too; here they are only read.
    auto& table = const_cast<Scene&>(scene).table<Kind>();
    std::apply([&](const auto&... c) { (h.column(c), ...); }, table.columns());
    if constexpr (requires { table.part_columns(); })
      std::apply([&](const auto&... c) { (h.column(c), ...); }, table.part_columns());
  });
}

// The settings' part, hashed after the scene's.
void hash_settings(Hasher& h, const PathSettings& settings) {
  h.value(settings.integrator), h.value(settings.seed);
  h.value(settings.max_depth), h.value(settings.rr_depth);
  // Hashed only when not the course's generator, so films from before samplers still fit.
  if (settings.sampler != Sampler::kMt19937) h.value(settings.sampler);
  if (settings.shading != Shading::kDouble) h.value(settings.shading);  // likewise
}

}  // namespace

uint64_t film_fingerprint(const Scene& scene, const PathSettings& settings) {
  Hasher h;
  hash_scene(h, scene);
  hash_settings(h, settings);
  return h.h;
}

void identify_film(Film& film, const Scene& scene, const PathSettings& settings) {
  Hasher with_settings;
  hash_scene(with_settings, scene);
  Hasher with_defaults = with_settings;  // scene_fingerprint: the same scene pass, reused
  hash_settings(with_settings, settings);
  hash_settings(with_defaults, PathSettings{});
  film.fingerprint = with_settings.h;
  film.origin = film_origin(with_defaults.h, settings);
}

Status save_film(const std::string& path, const Film& film) {
  std::string out(film.region ? kMagic3 : kMagic2, 8);
  const FilmOrigin& o = film.origin;
  uint32_t words[4] = {film.width, film.height, uint32_t(film.passes), uint32_t(o.integrator)};
  out.append(reinterpret_cast<const char*>(words), sizeof words);
  out.append(reinterpret_cast<const char*>(&film.fingerprint), 8);
  out.append(reinterpret_cast<const char*>(&o.scene), 8);
  out.append(reinterpret_cast<const char*>(&o.seed), 8);
  out.append(reinterpret_cast<const char*>(&o.max_depth), 4);
  out.append(reinterpret_cast<const char*>(&o.rr_depth), 4);
  out.append(reinterpret_cast<const char*>(&o.sampler), 4);
  out.append(reinterpret_cast<const char*>(&o.shading), 4);
  if (const auto& r = film.region) {
    const uint32_t corners[4] = {r->x0, r->y0, r->x1, r->y1};
    out.append(reinterpret_cast<const char*>(corners), sizeof corners);
  }
  // The sums go to the file straight from the film: a copy of them in memory would double
  // what a checkpoint of a large film needs.
  return write_file_atomically(path, [&](std::FILE* f) -> Status {
    auto put = [f](const void* data, std::size_t bytes) {
      return std::fwrite(data, 1, bytes, f) == bytes;
    };
    bool ok = put(out.data(), out.size()) && put(film.sum.data(), film.sum.size() * 8);
    if (ok && !film.aovs.empty())
      ok = put(kAovMagic, 4) && put(&film.aovs.bits, 4) &&
           put(film.aov_sum.data(), film.aov_sum.size() * 8);
    if (!ok) return Error{cat("write failed: ", std::strerror(errno))};
    return ok_status();
  });
}

Result<Film> load_film(const std::string& path) {
  auto file_size = regular_file_size(path);
  if (!file_size) return Error{cat(path, ": cannot read: ", file_size.error())};
  uint64_t size = *file_size;
  if (size < kHeader1) return Error{cat(path, ": expected a 32-byte film header, found ", size)};
  std::ifstream in(path, std::ios::binary);
  char head[kHeader2];
  if (!in.read(head, kHeader1)) return Error{cat(path, ": read failed")};
  const bool third = std::memcmp(head, kMagic3, 8) == 0;
  const bool second = third || std::memcmp(head, kMagic2, 8) == 0;
  if (!second && std::memcmp(head, kMagic1, 8) != 0)
    return Error{cat(path, ": expected a raylane film ('RLFILM2'), found another kind of file")};
  const std::size_t kHeader = second ? kHeader2 + (third ? kCorners : 0) : kHeader1;
  if (second && (size < kHeader || !in.read(head + kHeader1, kHeader2 - kHeader1)))
    return Error{
        cat(path, ": expected a film header of ", kHeader, " bytes, found ", size, " bytes")};
  Film f = read_header(head, second);
  uint32_t words[4];
  std::memcpy(words, head + 8, sizeof words);
  const uint64_t image_pixels = uint64_t(f.width) * f.height;
  if (image_pixels == 0 || image_pixels > kMaxImagePixels || words[2] > (1u << 30))
    return Error{cat(path, ": expected a film of 1 … 2^28 pixels, found ", f.width, "x", f.height,
                     " with ", words[2], " passes")};
  // The origin's enums are named in messages: a damaged header must not index past the names.
  const FilmOrigin& o = f.origin;
  if (o.integrator < 0 || std::size_t(o.integrator) >= kIntegratorNames.names.size() ||
      o.sampler < 0 || std::size_t(o.sampler) >= kSamplerNames.names.size() || o.shading < 0 ||
      std::size_t(o.shading) >= kShadingNames.names.size())
    return Error{cat(path, ": expected an integrator below ", kIntegratorNames.names.size(),
                     ", a sampler below ", kSamplerNames.names.size(), " and a shading below ",
                     kShadingNames.names.size(), " in the header, found ", o.integrator, ", ",
                     o.sampler, " and ", o.shading)};
  if (third) {
    char corners[kCorners];
    if (!in.read(corners, kCorners)) return Error{cat(path, ": read failed")};
    if (Status s = read_corners(corners, path, f); !s) return Error{s.error()};
  }
  const uint64_t pixels = f.stored_pixels();  // before a second-format region is read: all
  const uint64_t colour_end = kHeader + pixels * 24;
  if (size != colour_end && size < colour_end + kAovHeader)
    return Error{cat(path, ": a ", f.width, "x", f.height, " film",
                     third ? cat(" of the region ", region_text(*f.region)) : std::string(),
                     " has ", colour_end, " bytes, the file has ", size,
                     " (too few for AOVs after the colour)")};
  f.sum.resize(pixels * 3);
  if (!in.read(reinterpret_cast<char*>(f.sum.data()), std::streamsize(pixels * 24)))
    return Error{cat(path, ": read failed")};
  uint64_t after_colour = size - colour_end;
  if (!third)
    if (Status s = read_region(in, path, after_colour, f); !s) return Error{s.error()};
  if (after_colour > 0) {
    if (Status s = read_aovs(in, path, after_colour, pixels, f); !s) return Error{s.error()};
  }
  if (f.region && !third) {
    keep_region_only(f.sum, 3, f);
    if (!f.aovs.empty()) keep_region_only(f.aov_sum, std::size_t(f.aovs.channels()), f);
  }
  // A film raylane wrote holds finite sums only (non-finite samples are dropped before they
  // reach it), so anything else is damage, and continuing would spread it to the image.
  for (const std::vector<double>* sums : {&f.sum, &f.aov_sum}) {
    const std::size_t per_pixel = sums == &f.sum ? 3 : std::size_t(f.aovs.channels());
    for (std::size_t i = 0; i < sums->size(); ++i)
      if (!std::isfinite((*sums)[i]))
        return Error{cat(path, ": pixel ", i / per_pixel, " holds a non-finite ",
                         sums == &f.sum ? "sum" : "AOV sum", " (", (*sums)[i],
                         "): the film is damaged")};
  }
  return f;
}

}  // namespace raylane
