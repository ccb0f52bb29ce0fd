// libFuzzer target: scene text → Scene or diagnostics, parsed strict and --lenient (both
// paths must survive anything). Mesh lines look in the working directory, which the runner
// makes an empty folder, so they exercise the not-found path and the orientation parser.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "raylane/scene/parser.h"

namespace {

// A scene without errors must hold what the parser promised (spec, "Commands").
void check(const raylane::ParsedScene& parsed) {
  const raylane::Scene& s = parsed.scene;
  if (!parsed.ok()) return;
  if (!s.camera || s.width == 0 || s.height == 0 ||
      uint64_t(s.width) * s.height > raylane::kMaxImagePixels)
    std::abort();
  for (const raylane::Material& m : s.materials)  // a distribution the renderer knows; lights none
    if (m.microfacet > raylane::Microfacet::kBeckman ||
        (m.is_light && m.microfacet != raylane::Microfacet::kPhong))
      std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  std::string_view text(reinterpret_cast<const char*>(data), size);
  raylane::ParseOptions options;
  check(raylane::parse_scene(text, "fuzz.scn", options));
  options.lenient = true;
  check(raylane::parse_scene(text, "fuzz.scn", options));
  return 0;
}
