#include "args.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "raylane/core/strings.h"

namespace raylane::cli {

namespace {

const OptionSpec* find_long(const std::vector<OptionSpec>& specs, const std::string& name) {
  for (const auto& s : specs)
    if (s.name == name) return &s;
  return nullptr;
}

const OptionSpec* find_short(const std::vector<OptionSpec>& specs, char c) {
  for (const auto& s : specs)
    if (s.short_name != 0 && s.short_name == c) return &s;
  return nullptr;
}

}  // namespace

std::optional<std::string> ParsedArgs::last(const std::string& name) const {
  auto it = values.find(name);
  if (it == values.end() || it->second.empty()) return std::nullopt;
  return it->second.back();
}

Result<ParsedArgs> parse_args(const std::vector<std::string>& args,
                              const std::vector<OptionSpec>& specs) {
  ParsedArgs out;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--") {  // the end of the options: everything after is positional
      out.positional.insert(out.positional.end(), args.begin() + std::ptrdiff_t(i) + 1, args.end());
      break;
    }
    if (a.size() < 2 || a[0] != '-') {
      out.positional.push_back(a);
      continue;
    }
    const OptionSpec* spec = nullptr;
    std::optional<std::string> inline_value;
    if (a[1] == '-') {
      std::string name = a.substr(2);
      if (auto eq = name.find('='); eq != std::string::npos) {
        inline_value = name.substr(eq + 1);
        name = name.substr(0, eq);
      }
      spec = find_long(specs, name);
    } else if (a.size() == 2) {
      spec = find_short(specs, a[1]);
    }
    if (!spec) return Error{cat("unknown option ", in_quotes(a))};
    std::string value;
    if (spec->takes_value()) {
      if (inline_value) {
        value = *inline_value;
      } else if (i + 1 < args.size()) {
        value = args[++i];
      } else {
        return Error{cat("option --", spec->name, " needs a value")};
      }
    } else if (inline_value) {
      return Error{cat("option --", spec->name, " takes no value")};
    }
    auto& slot = out.values[spec->name];
    if (!spec->repeatable && !slot.empty())
      return Error{cat("option --", spec->name, " given more than once")};
    slot.push_back(value);
  }
  return out;
}

bool asks_for_help(const std::vector<std::string>& args, const std::vector<OptionSpec>& specs) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--") return false;
    if (a == "--help" || a == "-h") return true;
    // The value of an option that takes one is not a flag, even if it reads "-h".
    const OptionSpec* spec =
        a.rfind("--", 0) == 0 && a.find('=') == std::string::npos
            ? find_long(specs, a.substr(2))
            : (a.size() == 2 && a[0] == '-' ? find_short(specs, a[1]) : nullptr);
    if (spec && spec->takes_value()) ++i;
  }
  return false;
}

namespace {
constexpr std::size_t kHelpColumn = 22;  // where option descriptions start

std::string option_label(const OptionSpec& o) {
  std::string label =
      o.short_name ? cat("-", std::string(1, o.short_name), ", --", o.name) : cat("    --", o.name);
  if (o.takes_value()) label += " " + o.value_name;
  return label;
}

// Lines of `text` after `first`, each indented to the description column.
void append_described(std::string& out, const std::string& first, const std::string& text) {
  std::string line = "  " + first;
  std::istringstream lines(text);
  std::string part;
  bool any = false;
  while (std::getline(lines, part)) {
    if (!any && line.size() + 1 < kHelpColumn) {
      line.resize(kHelpColumn, ' ');
    } else {
      out += line + "\n";
      line = std::string(kHelpColumn, ' ');
    }
    line += part;
    any = true;
  }
  out += line + "\n";
}
}  // namespace

std::string format_help(const CommandHelp& help) {
  std::string out = cat("usage: ", help.usage, "\n\n", help.about, "\n");
  if (help.options && !help.options->empty()) {
    out += "\noptions:\n";
    for (const OptionSpec& o : *help.options) {
      std::string text = o.help;
      if (!o.default_text.empty()) text += cat("\n(default: ", o.default_text, ")");
      append_described(out, option_label(o), text);
    }
  }
  append_described(out, "-h, --help", "this text");
  if (!help.notes.empty()) out += "\n" + help.notes + "\n";
  return out;
}

int print_help(const CommandHelp& help) {
  std::fputs(format_help(help).c_str(), stdout);
  return 0;
}

Result<long> parse_int_option(const std::string& name, const std::string& value, long lo, long hi) {
  long v = 0;
  auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), v);
  if (ec != std::errc() || end != value.data() + value.size() || v < lo || v > hi)
    return Error{cat("--", name, " takes a whole number from ", lo, " to ", hi, ", found ",
                     in_quotes(value))};
  return v;
}

Result<double> parse_double_option(const std::string& name, const std::string& value) {
  double v = 0;
  auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), v);
  if (ec != std::errc() || end != value.data() + value.size() || !std::isfinite(v))
    return Error{cat("--", name, " takes a number, found ", in_quotes(value))};
  return v;
}

Status read_double_option(const std::string& name, const std::string& value, double& out) {
  auto v = parse_double_option(name, value);
  if (!v) return Error{v.error()};
  out = *v;
  return ok_status();
}

Result<Isa> parse_isa_option(const std::string& value) {
  if (value == "auto") return best_isa();
  auto isa = isa_from_name(value);
  if (!isa)
    return Error{cat("unknown --isa ", in_quotes(value), " (", kIsaNames.list(), ", auto)")};
  if (!isa_supported(*isa)) return Error{cat("this CPU cannot run --isa ", value)};
  return *isa;
}

}  // namespace raylane::cli
