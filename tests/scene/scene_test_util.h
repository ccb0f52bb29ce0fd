// Helpers for the scene tests: parse text and look at the diagnostics.
#pragma once

#include <string>
#include <vector>

#include <gmock/gmock.h>

#include "raylane/scene/parser.h"

namespace raylane::testing {

// A camera line, so that snippets that test something else parse without the
// "no camera line" error.
inline const char* kCameraLine = "camera 0 0 5 0.5\n";

inline ParsedScene parse(const std::string& text, bool lenient = false) {
  ParseOptions opts;
  opts.lenient = lenient;
  return parse_scene(text, "t.scn", opts);
}

inline std::vector<std::string> messages(const ParsedScene& p, Severity sev) {
  std::vector<std::string> out;
  for (const auto& d : p.diagnostics.items)
    if (d.severity == sev) out.push_back(to_string(d));
  return out;
}

inline std::vector<std::string> errors(const ParsedScene& p) {
  return messages(p, Severity::kError);
}
inline std::vector<std::string> warnings(const ParsedScene& p) {
  return messages(p, Severity::kWarning);
}

}  // namespace raylane::testing
