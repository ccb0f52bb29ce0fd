#include "raylane/core/strings.h"

#include <cstdint>
#include <cstdio>

namespace raylane {

namespace {

struct Invisible {
  uint32_t code;
  const char* name;
};

// Unicode's space separators and format characters that render as nothing or as a space.
constexpr Invisible kInvisible[] = {
    {0x00A0, "a no-break space"},
    {0x00AD, "a soft hyphen"},
    {0x1680, "an ogham space"},
    {0x2000, "an en quad"},
    {0x2001, "an em quad"},
    {0x2002, "an en space"},
    {0x2003, "an em space"},
    {0x2004, "a three-per-em space"},
    {0x2005, "a four-per-em space"},
    {0x2006, "a six-per-em space"},
    {0x2007, "a figure space"},
    {0x2008, "a punctuation space"},
    {0x2009, "a thin space"},
    {0x200A, "a hair space"},
    {0x200B, "a zero-width space"},
    {0x200C, "a zero-width non-joiner"},
    {0x200D, "a zero-width joiner"},
    {0x2028, "a line separator"},
    {0x2029, "a paragraph separator"},
    {0x202F, "a narrow no-break space"},
    {0x205F, "a mathematical space"},
    {0x2060, "a word joiner"},
    {0x3000, "an ideographic space"},
    {0xFEFF, "a byte-order mark"},
};

const char* invisible_name(uint32_t code) {
  for (const Invisible& i : kInvisible)
    if (i.code == code) return i.name;
  return nullptr;
}

// The code point of the UTF-8 sequence at s[i] and its length; 0 for a byte that starts no
// valid sequence.
int utf8_at(std::string_view s, std::size_t i, uint32_t& code) {
  auto b = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  unsigned char c = b(i);
  int n = c >= 0xF0 && c < 0xF5 ? 4 : c >= 0xE0 ? 3 : c >= 0xC2 && c < 0xE0 ? 2 : 0;
  if (n == 0 || i + n > s.size()) return 0;
  code = c & (0x7F >> n);
  for (int k = 1; k < n; ++k) {
    if ((b(i + k) & 0xC0) != 0x80) return 0;
    code = (code << 6) | (b(i + k) & 0x3F);
  }
  return n;
}

void append_hex(std::string& out, const char* format, unsigned v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, format, v);
  out += buf;
}

}  // namespace

std::string escape_invisible(std::string_view s) {
  std::string out;
  for (std::size_t i = 0; i < s.size();) {
    auto c = static_cast<unsigned char>(s[i]);
    if (c >= 0x20 && c < 0x7F) {
      out.push_back(char(c));
      ++i;
      continue;
    }
    uint32_t code = 0;
    int n = c >= 0x80 ? utf8_at(s, i, code) : 0;
    if (n > 0 && !invisible_name(code)) {
      out.append(s.substr(i, n));  // a visible character, e.g. an accented letter
    } else if (n > 0) {
      append_hex(out, "\\u%04X", code);
    } else {
      append_hex(out, "\\x%02X", c);
      n = 1;
    }
    i += std::size_t(n);
  }
  return out;
}

std::string first_invisible(std::string_view s) {
  for (std::size_t i = 0; i < s.size();) {
    auto c = static_cast<unsigned char>(s[i]);
    uint32_t code = 0;
    int n = c >= 0x80 ? utf8_at(s, i, code) : 0;
    if (n > 0 && invisible_name(code)) {
      std::string out = invisible_name(code);
      append_hex(out += " (", "\\u%04X", code);
      return out + ")";
    }
    if (c < 0x20 || c == 0x7F) {
      std::string out = c == 0 ? "a NUL byte" : c == 0x0B ? "a vertical tab" : "a control byte";
      append_hex(out += " (", "\\x%02X", c);
      return out + ")";
    }
    i += n > 0 ? std::size_t(n) : 1;
  }
  return "";
}

}  // namespace raylane
