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
  // Moving spheres: a radius > 0 and a swept box of finite floats at every time in [0, 1].
  const raylane::MovingSphereTable& mb = s.table<raylane::MovingSphere>();
  for (uint32_t i = 0; i < mb.size(); ++i) {
    const raylane::Bounds3f b = mb.bounds(i);
    if (!(mb.r[i] > 0) || !raylane::is_finite(b.lo) || !raylane::is_finite(b.hi)) std::abort();
  }
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
