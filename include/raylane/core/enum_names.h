// The names of an enum's values (0 … N−1, in order), read both ways: one table per enum for
// flags, messages and file headers.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace raylane {

template <class E, std::size_t N>
struct EnumNames {
  std::array<std::string_view, N> names;

  constexpr std::string_view name(E value) const { return names[std::size_t(value)]; }
  constexpr std::optional<E> from_name(std::string_view text) const {
    for (std::size_t i = 0; i < N; ++i)
      if (names[i] == text) return E(i);
    return std::nullopt;
  }
  // "a, b, c": for messages that list the choices.
  std::string list() const {
    std::string out;
    for (std::size_t i = 0; i < N; ++i)
      out.append(i ? ", " : "").append(names[i]);
    return out;
  }
};

}  // namespace raylane
