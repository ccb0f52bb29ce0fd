// The instruction sets raylane's packet tracer is compiled for, and the choice among them at
// run time. Baseline code includes this, never lanes.h.
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include "raylane/core/enum_names.h"

namespace raylane {

enum class Isa { kSse42, kAvx2, kAvx512 };

inline constexpr EnumNames<Isa, 3> kIsaNames{{"sse4.2", "avx2", "avx512"}};
inline std::string_view isa_name(Isa isa) {
  return kIsaNames.name(isa);
}
inline std::optional<Isa> isa_from_name(std::string_view name) {
  return kIsaNames.from_name(name);
}

int isa_width(Isa isa);             // float lanes: 4, 8, 16
bool isa_supported(Isa isa);        // by this CPU (cpuid)
Isa best_isa();                     // the widest supported
std::vector<Isa> supported_isas();  // narrowest first

// The one of three per-ISA things (a table of kernels) that belongs to `isa`.
template <class T>
const T& for_isa(Isa isa, const T& sse42, const T& avx2, const T& avx512) {
  switch (isa) {
    case Isa::kAvx512:
      return avx512;
    case Isa::kAvx2:
      return avx2;
    case Isa::kSse42:
      break;
  }
  return sse42;
}

}  // namespace raylane
