// Cursors over a PLY body (include/raylane/scene/ply.h): each reads the next value of a given
// type as a double (every PLY type converts to double exactly) and says where it is for errors.
// The ASCII cursor reads whitespace-separated numbers and counts lines and columns; the binary
// cursor reads fixed-size values in the file's byte order.
#pragma once

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include "raylane/core/strings.h"
#include "raylane/scene/ply.h"

namespace raylane::ply_detail {

inline std::size_t size_of(PlyType t) {
  switch (t) {
    case PlyType::kInt8:
    case PlyType::kUint8:
      return 1;
    case PlyType::kInt16:
    case PlyType::kUint16:
      return 2;
    case PlyType::kInt32:
    case PlyType::kUint32:
    case PlyType::kFloat32:
      return 4;
    case PlyType::kFloat64:
      return 8;
    case PlyType::kNone:
      break;
  }
  return 0;
}

inline bool is_integer_type(PlyType t) {
  return t != PlyType::kFloat32 && t != PlyType::kFloat64;
}

// The range of an integer type, for checking ASCII values against their declared type.
inline bool fits(PlyType t, double v) {
  switch (t) {
    case PlyType::kInt8:
      return v >= -128 && v <= 127;
    case PlyType::kUint8:
      return v >= 0 && v <= 255;
    case PlyType::kInt16:
      return v >= -32768 && v <= 32767;
    case PlyType::kUint16:
      return v >= 0 && v <= 65535;
    case PlyType::kInt32:
      return v >= -2147483648.0 && v <= 2147483647.0;
    case PlyType::kUint32:
      return v >= 0 && v <= 4294967295.0;
    default:
      return true;
  }
}

class AsciiCursor {
 public:
  AsciiCursor(std::string_view body, const std::string& name, int first_line)
      : body_(body), name_(name), line_(first_line) {}

  // The next number; on failure `error` says what was expected and what was found.
  bool read(PlyType type, double& out) {
    skip_space();
    std::size_t start = pos_;
    while (pos_ < body_.size() && !is_space(body_[pos_]))
      ++pos_;
    std::string_view token = body_.substr(start, pos_ - start);
    token_line_ = line_, token_col_ = int(start - line_start_) + 1;
    if (token.empty()) return fail(cat("expected a number, found the end of the file"));
    if (!parse(token, type, out))
      return fail(cat("expected ", is_integer_type(type) ? "an integer" : "a number",
                      " that fits the declared type, found ", in_quotes(token)));
    return true;
  }

  // Whether `n` more values can remain: each takes at least one byte.
  bool holds(uint64_t n, PlyType = PlyType::kNone) const { return body_.size() - pos_ >= n; }

  // "NAME:LINE:COL" of the last value read.
  std::string where() const { return cat(name_, ":", token_line_, ":", token_col_); }
  std::string error;

 private:
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

  void skip_space() {
    while (pos_ < body_.size() && is_space(body_[pos_])) {
      if (body_[pos_] == '\n') ++line_, line_start_ = pos_ + 1;
      ++pos_;
    }
  }

  static bool parse(std::string_view token, PlyType type, double& out) {
    if (token.size() > 1 && token[0] == '+' && token[1] != '-') token.remove_prefix(1);
    const char* end = token.data() + token.size();
    if (is_integer_type(type)) {
      int64_t i = 0;
      auto [p, ec] = std::from_chars(token.data(), end, i);
      if (ec == std::errc() && p == end) {
        out = double(i);
        return fits(type, out);
      }
    }
    auto [p, ec] = std::from_chars(token.data(), end, out);
    if (ec != std::errc() || p != end) return false;
    // The range first: converting a double beyond int64's range to an integer is undefined
    // (fuzz_mesh found "2.2e118" for an int property).
    if (is_integer_type(type)) return fits(type, out) && out == std::trunc(out);
    return true;
  }

  bool fail(std::string message) {
    error = cat(where(), ": ", message);
    return false;
  }

  std::string_view body_;
  const std::string& name_;
  std::size_t pos_ = 0, line_start_ = 0;
  int line_, token_line_ = 0, token_col_ = 0;
};

class BinaryCursor {
 public:
  BinaryCursor(std::string_view body, const std::string& name, uint64_t offset, bool big_endian)
      : body_(body),
        name_(name),
        offset_(offset),
        swap_(big_endian != (std::endian::native == std::endian::big)) {}

  bool read(PlyType type, double& out) {
    std::size_t n = size_of(type);
    at_ = pos_;
    if (body_.size() - pos_ < n) {
      error = cat(where(), ": expected ", n, " more bytes, found the end of the file");
      return false;
    }
    unsigned char b[8];
    std::memcpy(b, body_.data() + pos_, n);
    pos_ += n;
    if (swap_)
      for (std::size_t k = 0; k < n / 2; ++k)
        std::swap(b[k], b[n - 1 - k]);
    out = decode(type, b);
    return true;
  }

  // Whether `n` more bytes remain: a list's count is checked against it before its items.
  bool holds(uint64_t n) const { return body_.size() - pos_ >= n; }
  bool holds(uint64_t count, PlyType item) const { return holds(count * size_of(item)); }

  std::string where() const { return cat(name_, ": byte ", offset_ + at_); }
  std::string error;

 private:
  template <class T>
  static double as(const unsigned char* b) {
    T v;
    std::memcpy(&v, b, sizeof v);
    return double(v);
  }

  static double decode(PlyType type, const unsigned char* b) {
    switch (type) {
      case PlyType::kInt8:
        return as<int8_t>(b);
      case PlyType::kUint8:
        return as<uint8_t>(b);
      case PlyType::kInt16:
        return as<int16_t>(b);
      case PlyType::kUint16:
        return as<uint16_t>(b);
      case PlyType::kInt32:
        return as<int32_t>(b);
      case PlyType::kUint32:
        return as<uint32_t>(b);
      case PlyType::kFloat32:
        return as<float>(b);
      case PlyType::kFloat64:
        return as<double>(b);
      case PlyType::kNone:
        break;
    }
    return 0;
  }

  std::string_view body_;
  const std::string& name_;
  uint64_t offset_;
  bool swap_;
  std::size_t pos_ = 0, at_ = 0;
};

}  // namespace raylane::ply_detail
