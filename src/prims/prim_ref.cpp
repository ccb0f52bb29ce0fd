#include "raylane/prims/prim_ref.h"

namespace raylane {

std::string to_string(PrimRef ref) {
  if (!ref.valid()) return "none";
  static const char* const kNames[] = {"sphere", "box", "cylinder", "triangle"};
  uint32_t tag = uint32_t(ref.tag());
  std::string name = tag < 4 ? kNames[tag] : "kind" + std::to_string(tag);
  return name + "#" + std::to_string(ref.row());
}

}  // namespace raylane
