#include "raylane/render/film.h"

#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "raylane/core/atomic_file.h"
#include "raylane/core/input_file.h"
#include "raylane/core/strings.h"

namespace raylane {

namespace {

static_assert(std::endian::native == std::endian::little, "film files are little endian");

constexpr char kMagic[8] = {'R', 'L', 'F', 'I', 'L', 'M', '1', '\0'};
constexpr std::size_t kHeader = 32;

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
};

}  // namespace

Image Film::image() const {
  Image img(width, height);
  double scale = passes > 0 ? 1.0 / passes : 0.0;
  for (std::size_t i = 0; i < sum.size() && i < img.rgb.size(); ++i)
    img.rgb[i] = float(sum[i] * scale);
  return img;
}

uint64_t film_fingerprint(const Scene& scene, const PathSettings& settings) {
  Hasher h;
  h.value(scene.width), h.value(scene.height);
  if (scene.camera) {
    h.value(scene.camera->eye), h.value(scene.camera->ry), h.value(scene.camera->rotation);
  }
  for (const Material& m : scene.materials) {
    h.value(m.kd), h.value(m.ks), h.value(m.kt), h.value(m.alpha), h.value(m.ior);
    h.value(m.emission), h.value(m.is_light);
  }
  PrimKinds::for_each([&](auto kind) {
    // columns() hands out references for writing too; here they are only read.
    std::apply([&](const auto&... c) { (h.column(c), ...); },
               const_cast<Scene&>(scene).table<decltype(kind)>().columns());
  });
  h.value(settings.integrator), h.value(settings.seed);
  h.value(settings.max_depth), h.value(settings.rr_depth);
  return h.h;
}

Status save_film(const std::string& path, const Film& film) {
  std::string out(kMagic, 8);
  uint32_t words[4] = {film.width, film.height, uint32_t(film.passes), 0};
  out.append(reinterpret_cast<const char*>(words), sizeof words);
  out.append(reinterpret_cast<const char*>(&film.fingerprint), 8);
  out.append(reinterpret_cast<const char*>(film.sum.data()), film.sum.size() * sizeof(double));
  return write_file_atomically(path, out);
}

Result<Film> load_film(const std::string& path) {
  auto file_size = regular_file_size(path);
  if (!file_size) return Error{cat(path, ": cannot read: ", file_size.error())};
  uint64_t size = *file_size;
  if (size < kHeader) return Error{cat(path, ": expected a 32-byte film header, found ", size)};
  std::ifstream in(path, std::ios::binary);
  char head[kHeader];
  if (!in.read(head, kHeader)) return Error{cat(path, ": read failed")};
  if (std::memcmp(head, kMagic, 8) != 0)
    return Error{cat(path, ": expected a raylane film ('RLFILM1'), found another kind of file")};
  Film f;
  uint32_t words[4];
  std::memcpy(words, head + 8, sizeof words);
  std::memcpy(&f.fingerprint, head + 24, 8);
  f.width = words[0], f.height = words[1], f.passes = int(words[2]);
  uint64_t pixels = uint64_t(f.width) * f.height;
  if (pixels == 0 || pixels > kMaxImagePixels || words[2] > (1u << 30))
    return Error{cat(path, ": expected a film of 1 … 2^28 pixels, found ", f.width, "x", f.height,
                     " with ", words[2], " passes")};
  if (size != kHeader + pixels * 24)
    return Error{cat(path, ": a ", f.width, "x", f.height, " film has ", kHeader + pixels * 24,
                     " bytes, the file has ", size)};
  f.sum.resize(pixels * 3);
  if (!in.read(reinterpret_cast<char*>(f.sum.data()), std::streamsize(pixels * 24)))
    return Error{cat(path, ": read failed")};
  // A film raylane wrote holds finite sums only (non-finite samples are dropped before they
  // reach it), so anything else is damage, and continuing would spread it to the image.
  for (std::size_t i = 0; i < f.sum.size(); ++i)
    if (!std::isfinite(f.sum[i]))
      return Error{cat(path, ": pixel ", i / 3, " holds a non-finite sum (", f.sum[i],
                       "): the film is damaged")};
  return f;
}

}  // namespace raylane
