// A small command-line parser: `--name value`, `--name=value`, `-x value`, bare flags and
// positional arguments, and the help text of a command generated from its table of options.
// Unknown options are errors (exit status 2 in the caller).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "raylane/core/error.h"
#include "raylane/simd/isa.h"

namespace raylane::cli {

struct OptionSpec {
  std::string name;        // long name without dashes, e.g. "output"
  char short_name = 0;     // e.g. 'o', or 0
  std::string value_name;  // e.g. "FILE"; empty for a flag that takes no value
  bool repeatable = false;
  std::string help;          // what it does; '\n' starts another line
  std::string default_text;  // shown as "(default: …)" on a line of its own; empty: none

  bool takes_value() const { return !value_name.empty(); }
};

// What `raylane COMMAND --help` prints.
struct CommandHelp {
  std::string usage;  // e.g. "raylane render [SCENE] [options]"
  std::string about;  // a paragraph
  const std::vector<OptionSpec>* options = nullptr;
  std::string notes;  // after the options; may be empty
};

struct ParsedArgs {
  std::map<std::string, std::vector<std::string>> values;  // option name → values given
  std::vector<std::string> positional;

  bool has(const std::string& name) const { return values.count(name) > 0; }
  std::optional<std::string> last(const std::string& name) const;
};

Result<ParsedArgs> parse_args(const std::vector<std::string>& args,
                              const std::vector<OptionSpec>& specs);

// `--help` or `-h` among a command's arguments (before `--`, and not as an option's value).
bool asks_for_help(const std::vector<std::string>& args, const std::vector<OptionSpec>& specs);
std::string format_help(const CommandHelp& help);
// Prints the command's help on stdout; returns exit status 0.
int print_help(const CommandHelp& help);

// Converts an option value, naming the option in the error.
Result<long> parse_int_option(const std::string& name, const std::string& value, long lo, long hi);
Result<double> parse_double_option(const std::string& name, const std::string& value);
// --isa: sse4.2 | avx2 | avx512 | auto (the widest this CPU has); one the CPU lacks is an error.
Result<Isa> parse_isa_option(const std::string& value);

// The same, storing into `out`.
template <class Int>
Status read_int_option(const std::string& name, const std::string& value, long lo, long hi,
                       Int& out) {
  auto v = parse_int_option(name, value, lo, hi);
  if (!v) return Error{v.error()};
  out = Int(*v);
  return ok_status();
}
Status read_double_option(const std::string& name, const std::string& value, double& out);

}  // namespace raylane::cli
