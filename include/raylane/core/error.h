// Locations and diagnostics for bad input, printed as `file:line:col: message`, and a small
// Result<T> so library code reports errors without throwing across the API.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace raylane {

struct FileLoc {
  std::string file;
  int line = 0;  // 1-based; 0 = the file as a whole
  int col = 0;   // 1-based; 0 = the line as a whole
};

std::string to_string(const FileLoc& loc);

enum class Severity { kWarning, kError };

struct Diagnostic {
  Severity severity = Severity::kError;
  FileLoc loc;
  std::string message;
};

// "file:line:col: message" for errors, "file:line:col: warning: message" for warnings.
std::string to_string(const Diagnostic& d);

// Every diagnostic is counted; the first kMaxKept are kept with their text. A file of a
// million bad lines then costs a counter rather than a million messages, and its reader a
// screenful rather than a scroll (the first errors are the ones to fix first).
struct Diagnostics {
  static constexpr std::size_t kMaxKept = 200;
  std::vector<Diagnostic> items;  // the first kMaxKept, in order
  int errors = 0, warnings = 0;   // all of them, kept or not

  void error(FileLoc loc, std::string msg) {
    add(Severity::kError, std::move(loc), std::move(msg));
  }
  void warning(FileLoc loc, std::string msg) {
    add(Severity::kWarning, std::move(loc), std::move(msg));
  }
  int error_count() const { return errors; }
  int warning_count() const { return warnings; }
  // How many were counted but not kept.
  int dropped() const { return errors + warnings - int(items.size()); }

 private:
  void add(Severity s, FileLoc loc, std::string msg) {
    (s == Severity::kError ? errors : warnings) += 1;
    if (items.size() < kMaxKept) items.push_back({s, std::move(loc), std::move(msg)});
  }
};

struct Error {
  std::string message;
};

template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : v_(std::move(value)) {}
  Result(Error e) : v_(std::move(e)) {}

  bool ok() const { return v_.index() == 0; }
  explicit operator bool() const { return ok(); }
  T& value() { return std::get<0>(v_); }
  const T& value() const { return std::get<0>(v_); }
  T& operator*() { return value(); }
  T* operator->() { return &value(); }
  const std::string& error() const { return std::get<1>(v_).message; }

 private:
  std::variant<T, Error> v_;
};

// For operations that produce nothing but may fail.
struct Unit {};
using Status = Result<Unit>;
inline Status ok_status() {
  return Unit{};
}

}  // namespace raylane
