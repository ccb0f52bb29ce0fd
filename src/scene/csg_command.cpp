// `csg` … `end` blocks (docs/scene-language.md, "CSG blocks"): leaves and operators are written
// into a draft, which `end` appends to the CSG table as one row when the block is sound. Every
// problem is reported at its line; a block with one is never appended (under --lenient: skipped
// whole, with a warning at its `end`).
#include <array>
#include <span>

#include "block_lines.h"
#include "raylane/core/strings.h"

namespace raylane {

// The block being read.
struct CsgOpen {
  FileLoc at;          // its `csg` line
  CsgTable draft;      // its leaves and program so far
  uint32_t depth = 0;  // solids on its stack
  bool bad = false;    // a line of it was rejected
};

namespace {

constexpr std::array<std::string_view, 7> kBlockWords = {
    "csg", "end", "union", "intersect", "intersection", "difference", "subtraction"};

std::optional<uint32_t> operator_code(std::string_view w) {
  if (w == "union") return kCsgUnion;
  if (w == "intersect" || w == "intersection") return kCsgIntersect;
  if (w == "difference" || w == "subtraction") return kCsgDifference;
  return std::nullopt;
}

template <class Kind>
bool leaf_line(Scene& s, CsgOpen& b, const Line& line, ParseState& state) {
  auto v = parse_numbers(line, 1, Kind::param_count, true, state);
  if (!v) return false;
  CsgTable scratch;  // the parameters are checked before the material is taken
  auto params = std::span<const double, Kind::param_count>(v->data(), Kind::param_count);
  if (b.draft.leaves() >= kCsgMaxLeaves) {
    state.problem(line.at(0),
                  cat("a csg block holds at most ", kCsgMaxLeaves, " leaves, found one more"));
    return false;
  }
  if (auto err = scratch.add_leaf<Kind>(params, 0)) {
    state.problem(line.at(1 + std::max(err->param, 0)), err->message);
    return false;
  }
  auto mat = leaf_material(s, line, state, "a csg");
  if (!mat) return false;
  b.draft.add_leaf<Kind>(params, *mat);
  ++b.depth;
  return true;
}

bool operator_line(CsgOpen& b, uint32_t code, const Line& line, ParseState& state) {
  if (!no_parameters(line, state)) return false;
  if (b.depth < 2) {
    state.problem(line.at(0), cat(line.tokens[0].text,
                                  " pops two solids: expected at least 2 on "
                                  "the csg block's stack, found ",
                                  b.depth));
    return false;
  }
  b.draft.add_code(code);
  --b.depth;
  return true;
}

// Closes the block: appends it when it is sound.
void end_line(Scene& s, CsgOpen& b, const Line& line, ParseState& state) {
  bool ok = no_parameters(line, state);
  if (b.depth != 1) {
    state.problem(line.at(0), cat("end of the csg block opened at ", opened_at(b.at, line),
                                  ": expected exactly 1 solid on its stack, found ", b.depth));
    ok = false;
  }
  auto& table = s.table<Csg>();
  if (ok && !b.bad && table.leaves() + b.draft.leaves() >= PrimRef::kMaxRows) {
    state.problem(line.at(0), "too many csg leaves");
    ok = false;
  }
  if (!ok || b.bad) {
    if (state.options.lenient)
      state.diagnostics.warning(line.at(0), cat("skipped the csg block opened at ",
                                                opened_at(b.at, line), " whole: it has errors"));
    return;
  }
  if (!table.append_block(b.draft))
    state.diagnostics.warning(b.at,
                              "this csg block is empty (the bounds of its intersection "
                              "are empty): nothing was added");
}

bool line_in_block(Scene& s, CsgOpen& b, const Line& line, ParseState& state) {
  std::string_view w = line.tokens[0].text;
  if (w == "sphere") return leaf_line<Sphere>(s, b, line, state);
  if (w == "box") return leaf_line<Box>(s, b, line, state);
  if (w == "cylinder") return leaf_line<Cylinder>(s, b, line, state);
  if (auto code = operator_code(w)) return operator_line(b, *code, line, state);
  if (w == "brdf" || w == "microfacet") {
    // An ordinary material line: read with the block set aside, so it is not routed here again.
    std::shared_ptr<CsgOpen> open = std::move(state.csg_block);
    bool ok = s.command(line, state);
    state.csg_block = std::move(open);
    return ok;
  }
  if (w.starts_with("smooth") || w == "torus") {
    state.problem(line.at(0), cat(w,
                                  " belongs to sdf blocks only: not allowed inside the csg "
                                  "block opened at ",
                                  opened_at(b.at, line)));
    return false;
  }
  if (w == "csg" || w == "sdf") {
    state.problem(line.at(0), cat("a ", w,
                                  " block cannot be nested: expected end of the csg "
                                  "block opened at ",
                                  opened_at(b.at, line), ", found ", w));
    return false;
  }
  state.problem(line.at(0), cat(in_quotes(w), " is not allowed inside the csg block opened at ",
                                opened_at(b.at, line),
                                ": expected sphere, box, cylinder, brdf, "
                                "microfacet, union, intersect, difference or end"));
  return false;
}

}  // namespace

bool is_csg_word(std::string_view word) {
  for (std::string_view w : kBlockWords)
    if (word == w) return true;
  return false;
}

bool csg_command(Scene& s, const Line& line, ParseState& state) {
  std::string_view w = line.tokens[0].text;
  if (CsgOpen* b = state.csg_block.get()) {
    if (w == "end") {
      end_line(s, *b, line, state);
      state.csg_block.reset();
      return true;
    }
    bool ok = line_in_block(s, *b, line, state);
    b->bad = b->bad || !ok;
    return ok;
  }
  if (w == "csg") {  // opened even when the line has stray tokens, so its lines stay in it
    bool ok = no_parameters(line, state);
    state.csg_block = std::make_shared<CsgOpen>();
    state.csg_block->at = line.loc;
    state.csg_block->at.col = line.tokens[0].col;
    state.csg_block->bad = !ok;
    return ok;
  }
  state.problem(line.at(0), cat(w, " outside a block: expected a csg or sdf line before it"));
  return false;
}

void csg_end_of_input(ParseState& state) {
  if (!state.csg_block) return;
  const CsgOpen& b = *state.csg_block;
  state.problem(b.at, cat("expected end for this csg block, found the end of the input with ",
                          solids(b.depth), " on its stack"));
  state.csg_block.reset();
}

}  // namespace raylane
