#include "raylane/render/film/aov.h"

#include "raylane/core/strings.h"

namespace raylane {

Result<AovSet> parse_aov_list(const std::string& text) {
  AovSet set;
  std::size_t start = 0;
  while (true) {
    std::size_t comma = text.find(',', start);
    std::string name = text.substr(start, comma == std::string::npos ? comma : comma - start);
    auto aov = kAovNames.from_name(name);
    if (!aov)
      return Error{cat("--aov: expected a list of ", kAovNames.list(),
                       " separated by commas, found ", in_quotes(name))};
    if (set.has(*aov)) return Error{cat("--aov: ", name, " is listed twice")};
    set.bits |= 1u << unsigned(*aov);
    if (comma == std::string::npos) return set;
    start = comma + 1;
  }
}

std::string aov_list_text(AovSet set) {
  std::string out;
  for (std::size_t k = 0; k < kAovCount; ++k)
    if (set.has(Aov(k))) out.append(out.empty() ? "" : ", ").append(kAovNames.name(Aov(k)));
  return out;
}

}  // namespace raylane
