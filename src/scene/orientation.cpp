#include "raylane/scene/orientation.h"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "raylane/core/strings.h"

namespace raylane {

namespace {

// Number of numbers each rotation form takes.
int arity(std::string_view form) {
  if (form == "x" || form == "y" || form == "z") return 1;
  if (form == "a") return 4;
  if (form == "q") return 4;
  return -1;
}

std::optional<glm::dmat3> one_rotation(std::string_view form, const std::vector<double>& v,
                                       const FileLoc& loc, ParseState& state) {
  if (form == "x") return rotation_axis_angle({1, 0, 0}, v[0]);
  if (form == "y") return rotation_axis_angle({0, 1, 0}, v[0]);
  if (form == "z") return rotation_axis_angle({0, 0, 1}, v[0]);
  if (form == "a") {
    glm::dvec3 axis(v[1], v[2], v[3]);
    // Scaled by its largest component first, so a tiny axis (1e-200 …) does not square to 0.
    double big = std::max({std::abs(axis.x), std::abs(axis.y), std::abs(axis.z)});
    if (big > 0) axis = axis / big;
    double len = length(axis);
    if (!(len > 0.0) || !std::isfinite(len)) {
      state.problem(loc, "rotation axis must be non-zero");
      return std::nullopt;
    }
    return rotation_axis_angle(axis / len, v[0]);
  }
  double norm = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + v[3] * v[3]);
  if (!(norm > 0.0) || !std::isfinite(norm)) {
    state.problem(loc, "quaternion must be non-zero");
    return std::nullopt;
  }
  return glm::mat3_cast(glm::dquat(v[0] / norm, v[1] / norm, v[2] / norm, v[3] / norm));
}

// "x90" for "x 90": a rotation's letter and its first number written as one token. The hint
// names the two tokens; anything else gets none.
std::string run_together_hint(std::string_view form) {
  if (form.size() < 2 || arity(form.substr(0, 1)) < 0) return "";
  std::string_view number = form.substr(1);
  double v = 0;
  auto [end, ec] = std::from_chars(number.data(), number.data() + number.size(), v);
  if (ec != std::errc() || end != number.data() + number.size()) return "";
  return cat(" (write '", form.substr(0, 1), " ", number,
             "': the letter and its numbers are separate tokens)");
}

}  // namespace

std::optional<glm::dmat3> parse_orientation(const Line& line, std::size_t first,
                                            ParseState& state) {
  glm::dmat3 r = glm::dmat3(1.0);
  std::size_t i = first;
  while (i < line.tokens.size()) {
    std::string_view form = line.tokens[i].text;
    int n = arity(form);
    if (n < 0) {
      state.problem(line.at(i), cat("expected a rotation (x, y, z, a or q), found ",
                                    in_quotes(form), run_together_hint(form)));
      return std::nullopt;
    }
    std::size_t left = line.tokens.size() - i - 1;
    if (left < std::size_t(n)) {
      state.problem(line.at(i), cat("rotation '", form, "' takes ", n,
                                    n == 1 ? " number" : " numbers", ", found ", left));
      return std::nullopt;
    }
    std::vector<double> v;
    for (int k = 1; k <= n; ++k) {
      auto x = parse_number(line, i + k, state);
      if (!x) return std::nullopt;
      v.push_back(*x);
    }
    auto rot = one_rotation(form, v, line.at(i), state);
    if (!rot) return std::nullopt;
    r = r * *rot;  // the new rotation multiplies on the right
    i += n + 1;
  }
  return r;
}

}  // namespace raylane
