// Strict number reading for scene lines (docs/scene-language.md, "Lines and tokens").
#include <cfloat>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <string>

#include "hints.h"
#include "raylane/core/strings.h"
#include "raylane/scene/parse_state.h"
#include "raylane/scene/scene.h"

namespace raylane {

namespace {

// from_chars refuses a leading '+', which people do write.
std::from_chars_result read_double(std::string_view s, double& v) {
  const char* b = s.data();
  const char* e = b + s.size();
  if (b != e && *b == '+' && b + 1 != e && b[1] != '-' && b[1] != '+') ++b;
  return std::from_chars(b, e, v, std::chars_format::general);
}

// "expected a number" — pointing at an invisible character, if the token holds one (a
// no-break space pasted from a web page, a vertical tab), and saying what to do about it.
void not_a_number(std::string_view text, FileLoc loc, ParseState& state) {
  std::string invisible = first_invisible(text);
  if (invisible.empty()) {
    // "1,2,3" or "1,": numbers written as in a programming language.
    const bool comma = text.find(',') != std::string_view::npos;
    state.problem(loc, cat("expected a number, found ", in_quotes(text),
                           comma ? "; separate numbers with spaces, not commas" : ""));
    return;
  }
  for (std::size_t i = 0; i < text.size(); ++i) {
    auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 || c >= 0x7F) {
      loc.col += int(i);
      break;
    }
  }
  state.problem(loc, cat("expected a number, found ", in_quotes(text), ", which holds ", invisible,
                         ": write numbers with plain ASCII digits and separate them with spaces"));
}

}  // namespace

void ParseState::problem(const FileLoc& loc, std::string message) {
  if (options.lenient) {
    diagnostics.warning(loc, cat(message, " (line skipped)"));
  } else {
    diagnostics.error(loc, std::move(message));
  }
}

std::optional<double> parse_number(const Line& line, std::size_t token, ParseState& state) {
  std::string_view text = line.tokens[token].text;
  FileLoc loc = line.at(token);
  double v = 0;
  auto [end, ec] = read_double(text, v);
  bool complete = ec == std::errc() && end == text.data() + text.size();
  if (ec == std::errc::result_out_of_range) {
    // Too large, or too small for a double: strtod tells which (0 or a denormal for the
    // latter). A value too small underflows to zero, which is what a float would hold anyway.
    std::string copy(text.substr(text[0] == '+' ? 1 : 0));
    double near = std::strtod(copy.c_str(), nullptr);
    if (std::abs(near) > 1) {
      state.problem(loc, cat("number ", in_quotes(text), " does not fit in a float"));
      return std::nullopt;
    }
    v = std::copysign(0.0, near);
    ec = std::errc();
    complete = end == text.data() + text.size();
  }
  if (ec != std::errc()) {
    not_a_number(text, loc, state);
    return std::nullopt;
  }
  if (!std::isfinite(v)) {
    state.problem(loc, cat("expected a finite number, found ", in_quotes(text)));
    return std::nullopt;
  }
  if (std::abs(v) > FLT_MAX) {
    state.problem(loc, cat("number ", in_quotes(text), " does not fit in a float"));
    return std::nullopt;
  }
  if (!complete) {
    std::string_view prefix(text.data(), std::size_t(end - text.data()));
    if (!state.options.lenient) {
      not_a_number(text, loc, state);
      return std::nullopt;
    }
    state.diagnostics.warning(loc, cat("took the number ", prefix, " from ", in_quotes(text)));
  }
  return v;
}

std::optional<std::vector<double>> parse_numbers(const Line& line, std::size_t first,
                                                 std::size_t count, bool exact, ParseState& state) {
  std::size_t available = line.tokens.size() - std::min(first, line.tokens.size());
  if (available < count || (exact && available != count)) {
    state.problem(line.at(0), cat(line.tokens[0].text, " takes ", exact ? "" : "at least ", count,
                                  count == 1 ? " number" : " numbers", ", found ", available,
                                  comma_hint(line, first)));
    return std::nullopt;
  }
  std::vector<double> values;
  values.reserve(count);
  for (std::size_t i = first; i < first + count; ++i) {
    auto v = parse_number(line, i, state);
    if (!v) return std::nullopt;
    values.push_back(*v);
  }
  return values;
}

bool positive_in_float(double v, std::string_view what, const Line& line, std::size_t token,
                       ParseState& state) {
  if (v > 0 && float(v) > 0) return true;
  state.problem(line.at(token), v > 0 ? cat(what,
                                            " rounds to 0 in single precision; it must be > 0 "
                                            "after rounding (at least about 1.4e-45)")
                                      : cat(what, " must be > 0"));
  return false;
}

}  // namespace raylane
