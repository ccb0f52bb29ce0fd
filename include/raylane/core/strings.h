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

// A count and its noun as a message says them: "1 thread", "2 threads", "0 threads" (the noun
// takes a plain -s).
template <class Int>
std::string counted(Int n, std::string_view noun) {
  return cat(n, " ", noun, n == 1 ? "" : "s");
}

// Text as a message shows it: control bytes and bytes that are not UTF-8 as \xNN, and the
// Unicode characters that look like nothing (no-break and other spaces, zero-width
// characters, byte-order marks) as \uXXXX, so that a person sees what the file holds.
std::string escape_invisible(std::string_view s);

// The name of the first invisible character escape_invisible would show in `s` (e.g. "a
// no-break space (\u00A0)"), for messages that say what to do; empty if there is none.
std::string first_invisible(std::string_view s);

// A token as shown in a message: quoted, invisible bytes escaped, and cut short if long.
inline std::string in_quotes(std::string_view s) {
  constexpr std::size_t kShown = 40;
  if (s.size() > kShown) return cat("'", escape_invisible(s.substr(0, kShown)), "...'");
  return cat("'", escape_invisible(s), "'");
}

// A file name as shown in a message: quoted and whole (a path cut short names no file), with
// bytes that are not printable ASCII written as \xNN.
inline std::string quote_path(std::string_view s) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  std::string out = "'";
  for (char c : s) {
    auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u < 0x7f) {
      out.push_back(c);
    } else {
      out += "\\x";
      out.push_back(kHex[u >> 4]);
      out.push_back(kHex[u & 15]);
    }
  }
  return out + "'";
}

}  // namespace raylane
