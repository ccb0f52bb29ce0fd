#include "hints.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <vector>

#include "raylane/core/strings.h"
#include "raylane/scene/parse_state.h"
#include "raylane/scene/scene.h"

namespace raylane {

namespace {

// Every word that starts a scene line (docs/scene-language.md, "Commands", and the csg and
// sdf blocks).
constexpr std::array<std::string_view, 27> kCommands = {"screen",
                                                        "camera",
                                                        "ambient",
                                                        "lens",
                                                        "brdf",
                                                        "light",
                                                        "sphere",
                                                        "mbsphere",
                                                        "box",
                                                        "cylinder",
                                                        "mesh",
                                                        "texture",
                                                        "environment",
                                                        "microfacet",
                                                        "csg",
                                                        "end",
                                                        "union",
                                                        "intersect",
                                                        "intersection",
                                                        "difference",
                                                        "subtraction",
                                                        "sdf",
                                                        "torus",
                                                        "smooth",
                                                        "smoothunion",
                                                        "smoothintersect",
                                                        "smoothdifference"};

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out)
    c = char(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

}  // namespace

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
    row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string command_hint(std::string_view word) {
  const std::string low = lower(word);
  for (std::string_view c : kCommands)
    if (low == c) return cat("; did you mean ", in_quotes(c), "? (commands are lower case)");
  // Long words only: comparing a long token with every command costs |word| × |command|.
  if (word.size() > 32) return "";
  // One edit in three letters, at least one and at most two: 'shpere' finds 'sphere', while
  // 'bogus' (two edits from 'torus') finds nothing.
  const std::size_t allowed = std::clamp<std::size_t>(word.size() / 3, 1, 2);
  std::string_view best;
  std::size_t best_distance = allowed + 1;
  bool tie = false;
  for (std::string_view c : kCommands) {
    const std::size_t d = edit_distance(low, c);
    if (d < best_distance) {
      best = c, best_distance = d, tie = false;
    } else if (d == best_distance) {
      tie = true;
    }
  }
  if (best.empty() || tie) return "";
  return cat("; did you mean ", in_quotes(best), "?");
}

std::string comma_hint(const Line& line, std::size_t first) {
  for (std::size_t i = first; i < line.tokens.size(); ++i)
    if (!line.tokens[i].quoted && line.tokens[i].text.find(',') != std::string_view::npos)
      return "; separate numbers with spaces, not commas";
  return "";
}

std::string spaced_name_hint(const Line& line, std::size_t at, const ParseState& state) {
  if (at >= line.tokens.size() || line.tokens[at].quoted) return "";
  const char* begin = line.tokens[at].text.data();
  // Tokens point into the line as written, so tokens at..k span the name with its spaces.
  for (std::size_t k = at + 1; k < line.tokens.size(); ++k) {
    const std::string_view last = line.tokens[k].text;
    const std::string name(begin, std::size_t(last.data() + last.size() - begin));
    if (find_input_file(state, name))
      return cat("; the file name ", quote_path(name), " holds a space: quote it, \"", name, "\"");
  }
  return "";
}

}  // namespace raylane
