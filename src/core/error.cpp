#include "raylane/core/error.h"

#include "raylane/core/strings.h"

namespace raylane {

std::string to_string(const FileLoc& loc) {
  std::string s = escape_invisible(loc.file);  // a name with a control byte stays readable
  if (loc.line > 0) s.append(":").append(std::to_string(loc.line));
  if (loc.line > 0 && loc.col > 0) s.append(":").append(std::to_string(loc.col));
  return s;
}

std::string to_string(const Diagnostic& d) {
  std::string s = to_string(d.loc);
  s.append(": ");
  if (d.severity == Severity::kWarning) s.append("warning: ");
  return s.append(d.message);
}

}  // namespace raylane
