// PrimTag and PrimRef: how any primitive of any kind is named (docs/design.md, "Tagged dispatch").
#pragma once

#include <cstdint>
#include <string>

namespace raylane {

// A primitive kind's position in the kind list: tag_of<Kind> (prim_list.h) derives it, so the
// list is the one place that orders the kinds.
enum class PrimTag : uint32_t {};

// A kind tag and a row index packed in 32 bits: 3 bits of tag (room for 8 kinds) and 29 bits
// of row, so a table holds at most 2^29 rows; the scene checks that bound before appending.
class PrimRef {
 public:
  static constexpr int kTagBits = 3;
  static constexpr int kRowBits = 32 - kTagBits;
  static constexpr uint32_t kMaxRows = 1u << kRowBits;
  static constexpr uint32_t kInvalidBits = ~0u;

  constexpr PrimRef() = default;
  constexpr PrimRef(PrimTag tag, uint32_t row)
      : bits_((uint32_t(tag) << kRowBits) | (row & (kMaxRows - 1))) {}
  static constexpr PrimRef invalid() { return PrimRef(kInvalidBits); }
  static constexpr PrimRef from_bits(uint32_t bits) { return PrimRef(bits); }

  constexpr PrimTag tag() const { return PrimTag(bits_ >> kRowBits); }
  constexpr uint32_t row() const { return bits_ & (kMaxRows - 1); }
  constexpr uint32_t bits() const { return bits_; }
  constexpr bool valid() const { return bits_ != kInvalidBits; }
  friend constexpr bool operator==(PrimRef a, PrimRef b) { return a.bits_ == b.bits_; }
  friend constexpr bool operator!=(PrimRef a, PrimRef b) { return a.bits_ != b.bits_; }
  friend constexpr bool operator<(PrimRef a, PrimRef b) { return a.bits_ < b.bits_; }

 private:
  constexpr explicit PrimRef(uint32_t bits) : bits_(bits) {}
  uint32_t bits_ = kInvalidBits;
};

// Why a row could not be appended: the 0-based index of the offending parameter (−1 for the
// row as a whole) and what was wrong.
struct ParamError {
  int param = -1;
  std::string message;
};

}  // namespace raylane
