// `sdf` … `end` blocks (docs/scene-language.md, "SDF blocks"): leaves and
// operators are written into the SDF table's columns beside its rows as they are read, and
// `end` appends the block's row when the block is sound. Every problem is reported at its
// line; a block with one is dropped whole (under --lenient: with a warning at its `end`).
#include <span>

#include "block_lines.h"
#include "raylane/core/strings.h"

namespace raylane {

// The block being read.
struct SdfOpen {
  FileLoc at;          // its `sdf` line
  uint32_t depth = 0;  // solids on its stack
  bool bad = false;    // a line of it was rejected
};

namespace {

std::optional<uint32_t> operator_code(std::string_view w) {
  if (w == "union") return kSdfUnion;
  if (w == "intersect" || w == "intersection") return kSdfIntersect;
  if (w == "difference" || w == "subtraction") return kSdfDifference;
  if (w == "smoothunion") return kSdfSmoothUnion;
  if (w == "smoothintersect") return kSdfSmoothIntersect;
  if (w == "smoothdifference") return kSdfSmoothDifference;
  return std::nullopt;
}

template <std::size_t N, class Add>
bool leaf_line(Scene& s, SdfOpen& b, const Line& line, ParseState& state, const Add& add) {
  auto v = parse_numbers(line, 1, N, true, state);
  if (!v) return false;
  SdfTable& table = s.table<Sdf>();
  if (table.open_leaves() >= kSdfMaxLeaves) {
    state.problem(line.at(0),
                  cat("an sdf block holds at most ", kSdfMaxLeaves, " leaves, found one more"));
    return false;
  }
  SdfTable scratch;  // the parameters are checked before the material is taken
  auto params = std::span<const double, N>(v->data(), N);
  if (auto err = add(scratch, params, 0)) {
    state.problem(line.at(1 + std::max(err->param, 0)), err->message);
    return false;
  }
  auto mat = leaf_material(s, line, state, "an sdf");
  if (!mat) return false;
  add(table, params, *mat);
  ++b.depth;
  return true;
}

// A smooth operator's width k: > 0 in float. The number reader rejects what is not finite in
// float (nan, inf, 1e39) with its own messages.
std::optional<float> smooth_width(const Line& line, ParseState& state) {
  auto v = parse_numbers(line, 1, 1, true, state);
  if (!v) return std::nullopt;
  if (!positive_in_float((*v)[0], cat(line.tokens[0].text, " width k"), line, 1, state))
    return std::nullopt;
  return float((*v)[0]);
}

bool operator_line(Scene& s, SdfOpen& b, uint32_t code, const Line& line, ParseState& state) {
  float k = 0;
  if (sdf_is_smooth(code)) {
    auto width = smooth_width(line, state);
    if (!width) return false;
    k = *width;
  } else if (!no_parameters(line, state)) {
    return false;
  }
  if (b.depth < 2) {
    state.problem(line.at(0), cat(line.tokens[0].text,
                                  " pops two solids: expected at least 2 on the sdf block's "
                                  "stack, found ",
                                  b.depth));
    return false;
  }
  s.table<Sdf>().add_code(code, k);
  --b.depth;
  return true;
}

// Closes the block: appends its row when it is sound, else drops what it wrote.
void end_line(Scene& s, SdfOpen& b, const Line& line, ParseState& state) {
  bool ok = no_parameters(line, state);
  if (b.depth != 1) {
    state.problem(line.at(0), cat("end of the sdf block opened at ", opened_at(b.at, line),
                                  ": expected exactly 1 solid on its stack, found ", b.depth));
    ok = false;
  }
  SdfTable& table = s.table<Sdf>();
  if (ok && !b.bad && table.leaves() >= PrimRef::kMaxRows) {
    state.problem(line.at(0), "too many sdf leaves");
    ok = false;
  }
  if (!ok || b.bad) {
    table.drop_block();
    if (state.options.lenient)
      state.diagnostics.warning(line.at(0), cat("skipped the sdf block opened at ",
                                                opened_at(b.at, line), " whole: it has errors"));
    return;
  }
  if (!table.end_block())
    state.diagnostics.warning(b.at,
                              "this sdf block is empty (the bounds of its intersection "
                              "are empty): nothing was added");
}

bool line_in_block(Scene& s, SdfOpen& b, const Line& line, ParseState& state) {
  std::string_view w = line.tokens[0].text;
  auto add = [](auto kind) {
    using Kind = decltype(kind);
    return [](SdfTable& t, std::span<const double, Kind::param_count> p, uint32_t m) {
      return t.add_leaf<Kind>(p, m);
    };
  };
  if (w == "sphere") return leaf_line<4>(s, b, line, state, add(Sphere{}));
  if (w == "box") return leaf_line<6>(s, b, line, state, add(Box{}));
  if (w == "cylinder") return leaf_line<7>(s, b, line, state, add(Cylinder{}));
  if (w == "torus")
    return leaf_line<8>(
        s, b, line, state,
        [](SdfTable& t, std::span<const double, 8> p, uint32_t m) { return t.add_torus(p, m); });
  if (auto code = operator_code(w)) return operator_line(s, b, *code, line, state);
  if (w == "brdf" || w == "microfacet") {
    // An ordinary material line: read with the block set aside, so it is not routed here again.
    std::shared_ptr<SdfOpen> open = std::move(state.sdf_block);
    bool ok = s.command(line, state);
    state.sdf_block = std::move(open);
    return ok;
  }
  if (w == "csg" || w == "sdf") {
    state.problem(line.at(0), cat("a ", w,
                                  " block cannot be nested: expected end of the sdf block "
                                  "opened at ",
                                  opened_at(b.at, line), ", found ", w));
    return false;
  }
  state.problem(line.at(0), cat(in_quotes(w), " is not allowed inside the sdf block opened at ",
                                opened_at(b.at, line),
                                ": expected sphere, box, cylinder, torus, brdf, microfacet, "
                                "union, intersect, difference, their smooth forms or end"));
  return false;
}

}  // namespace

bool is_sdf_word(std::string_view word) {
  return word == "sdf" || word == "torus" || word.starts_with("smooth");
}

bool sdf_command(Scene& s, const Line& line, ParseState& state) {
  std::string_view w = line.tokens[0].text;
  if (SdfOpen* b = state.sdf_block.get()) {
    if (w == "end") {
      end_line(s, *b, line, state);
      state.sdf_block.reset();
      return true;
    }
    bool ok = line_in_block(s, *b, line, state);
    b->bad = b->bad || !ok;
    return ok;
  }
  if (w == "sdf") {  // opened even when the line has stray tokens, so its lines stay in it
    bool ok = no_parameters(line, state);
    state.sdf_block = std::make_shared<SdfOpen>();
    state.sdf_block->at = line.loc;
    state.sdf_block->at.col = line.tokens[0].col;
    state.sdf_block->bad = !ok;
    s.table<Sdf>().begin_block();
    return ok;
  }
  state.problem(line.at(0), cat(w, " outside a block: expected an sdf line before it"));
  return false;
}

void sdf_end_of_input(Scene& s, ParseState& state) {
  if (!state.sdf_block) return;
  const SdfOpen& b = *state.sdf_block;
  state.problem(b.at, cat("expected end for this sdf block, found the end of the input with ",
                          solids(b.depth), " on its stack"));
  s.table<Sdf>().drop_block();
  state.sdf_block.reset();
}

}  // namespace raylane
