// A small command-line parser: `--name value`, `--name=value`, `-x value`, bare flags and
// positional arguments. Unknown options are errors (exit status 2 in the caller).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "raylane/core/error.h"
#include "raylane/simd/isa.h"

namespace raylane::cli {

struct OptionSpec {
  std::string name;     // long name without dashes, e.g. "output"
  char short_name = 0;  // e.g. 'o', or 0
  bool takes_value = false;
  bool repeatable = false;
};

struct ParsedArgs {
  std::map<std::string, std::vector<std::string>> values;  // option name → values given
  std::vector<std::string> positional;

  bool has(const std::string& name) const { return values.count(name) > 0; }
  std::optional<std::string> last(const std::string& name) const;
};

Result<ParsedArgs> parse_args(const std::vector<std::string>& args,
                              const std::vector<OptionSpec>& specs);

// Converts an option value, naming the option in the error.
Result<long> parse_int_option(const std::string& name, const std::string& value, long lo, long hi);
Result<double> parse_double_option(const std::string& name, const std::string& value);
// --isa: sse4.2 | avx2 | avx512 | auto (the widest this CPU has); one the CPU lacks is an error.
Result<Isa> parse_isa_option(const std::string& value);

}  // namespace raylane::cli
