#include "file_kind.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <vector>

#include "raylane/core/strings.h"

namespace raylane::cli {

namespace {

namespace fs = std::filesystem;

// How much of a file is looked at: enough for every magic number and a few lines of text.
constexpr std::size_t kHeadBytes = 4096;

constexpr const char* kMeshAdvice =
    "a scene places a mesh with `mesh FILE x y z s <orientation>` "
    "(docs/scene-language.md, \"mesh\")";
constexpr const char* kImageAdvice =
    "a scene reads images with `texture FILE` or `environment FILE s` "
    "(docs/scene-language.md, \"Images\"); `raylane convert` turns it into another format";
constexpr const char* kOtherSceneAdvice =
    "raylane reads the CS500 scene language (docs/scene-language.md); its meshes can be placed "
    "with `mesh`";

struct Magic {
  std::string_view bytes;  // the file's first bytes
  const char* what;
  const char* advice;  // "%s" stands for the file's path
};

// Files recognised by their first bytes (the formats' own specifications: the PNG signature,
// JPEG's SOI marker and the first segment's FF, the EXR magic 20000630 little endian, ...).
constexpr Magic kMagics[] = {
    {{"RLFILM1\0", 8},
     "a raylane film",
     "continue it with `raylane render SCENE --resume %s`; `raylane info %s` shows what it holds"},
    {{"RLFILM2\0", 8},
     "a raylane film",
     "continue it with `raylane render SCENE --resume %s`; `raylane info %s` shows what it holds"},
    {{"RLFILM3\0", 8},
     "a raylane film of a --region",
     "continue it with `raylane render SCENE --region ... --resume %s`; `raylane info %s` shows "
     "what it holds"},
    {{"RAYSET1\0", 8}, "a ray set (.rays)", "`raylane trace MESH %s` traces it (docs/ray-sets.md)"},
    {"TRISOUP1", "a triangle soup (.tris)",
     "`raylane trace %s RAYS` traces a ray set against it (docs/ray-sets.md)"},
    {{"HITS001\0", 8},
     "the answers of a ray set (.hits)",
     "`raylane trace` writes these (docs/ray-sets.md)"},
    {"ply\n", "a PLY mesh", kMeshAdvice},
    {"ply\r\n", "a PLY mesh", kMeshAdvice},
    {"glTF", "a binary glTF mesh", kMeshAdvice},
    {"Kaydara FBX Binary", "an FBX mesh", kMeshAdvice},
    {"xof ", "a DirectX mesh", kMeshAdvice},
    {"\x89PNG\r\n\x1a\n", "a PNG image", kImageAdvice},
    {"\xff\xd8\xff", "a JPEG image", kImageAdvice},
    {"#?RADIANCE", "a Radiance HDR image", kImageAdvice},
    {"#?RGBE", "a Radiance HDR image", kImageAdvice},
    {"PF\n", "a PFM image", kImageAdvice},
    {"Pf\n", "a PFM image", kImageAdvice},
    {"v/1\x01", "an OpenEXR image", kImageAdvice},
    {"BLENDER", "a Blender file", kOtherSceneAdvice},
};

bool starts_with(std::string_view s, std::string_view prefix) {
  return s.substr(0, prefix.size()) == prefix;
}

// Control bytes other than white space: text has none, binary formats many.
bool looks_binary(std::string_view head) {
  std::size_t control = 0;
  for (unsigned char c : head)
    control +=
        (c < 0x20 && c != '\t' && c != '\n' && c != '\r' && c != '\f' && c != '\v') || c == 0x7f;
  return control * 16 > head.size();  // more than 1 byte in 16: a stray NUL in text is not
}

// The first word of each line of the head (the last line may be cut short; it still counts).
std::vector<std::string_view> first_words(std::string_view head) {
  std::vector<std::string_view> words;
  std::size_t at = 0;
  while (at < head.size()) {
    std::size_t end = std::min(head.find('\n', at), head.size());
    std::string_view line = head.substr(at, end - at);
    std::size_t b = line.find_first_not_of(" \t\r");
    if (b != std::string_view::npos) {
      std::size_t e = std::min(line.find_first_of(" \t\r", b), line.size());
      words.push_back(line.substr(b, e - b));
    }
    at = end + 1;
  }
  return words;
}

// pbrt's directives are capitalised; the CS500 language's commands are not. One directive could
// be a typo in a scene, so two different ones (or WorldBegin, which only pbrt has) are needed.
bool looks_like_pbrt(const std::vector<std::string_view>& words) {
  static constexpr std::string_view kDirectives[] = {
      "LookAt",    "Camera",      "Film",       "Sampler",        "Integrator",
      "Shape",     "LightSource", "WorldBegin", "AttributeBegin", "Material",
      "Translate", "Rotate",      "Scale",      "Texture",        "PixelFilter"};
  std::vector<std::string_view> seen;
  for (std::string_view w : words) {
    if (w == "WorldBegin") return true;
    if (std::find(std::begin(kDirectives), std::end(kDirectives), w) != std::end(kDirectives) &&
        std::find(seen.begin(), seen.end(), w) == seen.end())
      seen.push_back(w);
  }
  return seen.size() >= 2;
}

// Wavefront OBJ: vertex and face lines; the CS500 language has neither command.
bool looks_like_obj(const std::vector<std::string_view>& words) {
  bool v = false, f = false;
  for (std::string_view w : words)
    v |= w == "v", f |= w == "f";
  return v && f;
}

std::string lower_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

std::string with_path(const char* advice, const std::string& path) {
  std::string out;
  for (const char* c = advice; *c; ++c) {
    if (c[0] == '%' && c[1] == 's') {
      out += path;
      ++c;
    } else {
      out += *c;
    }
  }
  return out;
}

std::string described(const char* what, const char* advice, const std::string& path) {
  return cat(what, ", not a scene: ", with_path(advice, path));
}

std::string directory_message(const std::string& path) {
  std::vector<std::string> scenes;
  std::error_code ec;
  for (fs::directory_iterator it(path, ec), end; !ec && it != end; it.increment(ec))
    if (it->path().extension() == ".scn") scenes.push_back(it->path().filename().string());
  std::sort(scenes.begin(), scenes.end());
  std::string listed;
  for (std::size_t i = 0; i < scenes.size() && i < 4; ++i)
    listed += cat(i ? ", " : "", scenes[i]);
  if (scenes.size() > 4) listed += ", ...";
  return cat(path, ": a directory, not a scene file: name a .scn file",
             scenes.empty() ? std::string(" (it holds none)") : cat(" (it holds ", listed, ")"));
}

}  // namespace

std::optional<std::string> foreign_kind(std::string_view head, const std::string& path) {
  for (const Magic& m : kMagics)
    if (starts_with(head, m.bytes)) return described(m.what, m.advice, path);
  if (starts_with(head, "BM") && looks_binary(head))
    return described("a BMP image", kImageAdvice, path);
  std::vector<std::string_view> words = first_words(head);
  if (head.find("<COLLADA") != std::string_view::npos)
    return described("a Collada mesh", kMeshAdvice, path);
  if (head.find("<scene") != std::string_view::npos &&
      head.find("version=") != std::string_view::npos)
    return described("a Mitsuba scene", kOtherSceneAdvice, path);
  if (looks_like_pbrt(words)) return described("a pbrt scene", kOtherSceneAdvice, path);
  if (looks_like_obj(words)) return described("a Wavefront OBJ mesh", kMeshAdvice, path);
  std::string ext = lower_extension(path);
  if (starts_with(head, "solid ") && ext == ".stl")
    return described("an STL mesh", kMeshAdvice, path);
  if (looks_binary(head)) {
    static constexpr std::string_view kImages[] = {".tga",  ".bmp", ".png", ".jpg",
                                                   ".jpeg", ".exr", ".hdr", ".pfm"};
    if (std::find(std::begin(kImages), std::end(kImages), ext) != std::end(kImages))
      return described("an image (by its name)", kImageAdvice, path);
    return cat(
        "binary data, not a scene: a scene is text in the CS500 scene language "
        "(docs/scene-language.md)");
  }
  return std::nullopt;
}

std::optional<std::string> not_a_scene(const std::string& path) {
  std::error_code ec;
  fs::file_status st = fs::status(path, ec);
  if (ec) return std::nullopt;
  if (fs::is_directory(st)) return directory_message(path);
  if (!fs::is_regular_file(st)) return std::nullopt;  // a FIFO is never opened here
  std::ifstream in(path, std::ios::binary);
  std::string head(kHeadBytes, '\0');
  in.read(head.data(), std::streamsize(head.size()));
  head.resize(std::size_t(in.gcount()));
  auto kind = foreign_kind(head, path);
  if (!kind) return std::nullopt;
  return cat(path, ": ", *kind);
}

}  // namespace raylane::cli
