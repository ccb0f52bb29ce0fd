// JSON text for the commands' machine-readable summaries (render's and trace's --stats-json):
// strings escaped and kept UTF-8 whatever bytes a file name holds, numbers that read back to
// the same double, objects built one member at a time.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "raylane/core/strings.h"

namespace raylane::cli {

// A JSON string: quotes, backslashes and control bytes escaped (RFC 8259, section 7); each
// byte that starts no well-formed UTF-8 sequence becomes U+FFFD, so the text stays JSON.
std::string json_string(std::string_view s);
// A JSON number with 17 significant digits; null for NaN and infinities (JSON has neither).
std::string json_number(double v);
// ["a", "b", ...]
std::string json_string_array(const std::vector<std::string>& v);

// Builds `{"key": value, ...}` one member at a time.
class JsonObject {
 public:
  JsonObject& raw(std::string_view key, const std::string& value) {
    text_ += cat(text_.empty() ? "{" : ", ", json_string(key), ": ", value);
    return *this;
  }
  JsonObject& number(std::string_view key, double v) { return raw(key, json_number(v)); }
  JsonObject& count(std::string_view key, uint64_t v) { return raw(key, std::to_string(v)); }
  JsonObject& string(std::string_view key, std::string_view v) { return raw(key, json_string(v)); }
  JsonObject& boolean(std::string_view key, bool v) { return raw(key, v ? "true" : "false"); }
  std::string str() const { return text_.empty() ? "{}" : text_ + "}"; }

 private:
  std::string text_;
};

}  // namespace raylane::cli
