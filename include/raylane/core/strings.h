// cat(...): builds a message from strings and numbers. Appending piece by piece also avoids
// GCC 12's false -Wrestrict warning on `"literal" + std::string` (GCC bug 105651).
#pragma once

#include <string>
#include <string_view>
#include <type_traits>

namespace raylane {

namespace detail {
inline void append_piece(std::string& s, std::string_view v) {
  s.append(v);
}
inline void append_piece(std::string& s, char c) {
  s.push_back(c);
}
template <class T, class = std::enable_if_t<std::is_arithmetic_v<T>>>
void append_piece(std::string& s, T v) {
  s.append(std::to_string(v));
}
}  // namespace detail

template <class... Pieces>
std::string cat(const Pieces&... pieces) {
  std::string s;
  (detail::append_piece(s, pieces), ...);
  return s;
}

// A token as shown in a message: quoted, and cut short if long.
inline std::string in_quotes(std::string_view s) {
  constexpr std::size_t kShown = 40;
  if (s.size() > kShown) return cat("'", s.substr(0, kShown), "...'");
  return cat("'", s, "'");
}

}  // namespace raylane
