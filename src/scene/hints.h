// Hints appended to parse errors for the slips people make most (docs/scene-language.md,
// "Hints"): a command in the wrong case or misspelt, numbers separated by commas, a file name
// with a space left unquoted. Each returns the text to append to the error ("" for none), so
// the error keeps its `file:line:col: expected X, found Y` form and gains a sentence.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace raylane {

struct Line;
struct ParseState;

// For an unknown command: "; did you mean 'sphere'? (commands are lower case)" when the word
// is a command in another case, "; did you mean 'sphere'?" when one command alone is nearest
// to it, within an edit distance of one per three letters (at least 1, at most 2).
std::string command_hint(std::string_view word);

// The edit distance (Levenshtein: insertions, deletions, substitutions) of a and b.
std::size_t edit_distance(std::string_view a, std::string_view b);

// For a token that is not a number, or a count of numbers that is wrong: when a token of the
// line from `first` on holds a comma, "; separate numbers with spaces, not commas".
std::string comma_hint(const Line& line, std::size_t first);

// For a line whose file name (token `at`) is followed by what is not a number or by too many
// tokens: when tokens at..k, as written with their spaces, name a file that exists,
// "; the file name 'my model.ply' holds a space: quote it, \"my model.ply\"".
std::string spaced_name_hint(const Line& line, std::size_t at, const ParseState& state);

}  // namespace raylane
