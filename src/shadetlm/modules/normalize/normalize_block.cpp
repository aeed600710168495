// The normalize block's declaration (tlm/block.hpp).
#include "shadetlm/core/input_error.hpp"
#include "shadetlm/tlm/block.hpp"
#include "shadetlm/modules/normalize/normalize_kernel.hpp"
#include "shadetlm/modules/normalize/normalize_rtl.hpp"

namespace shadetlm::modules {

namespace {
// Each mode's critical path, unit after unit (docs/configuration.md, "Arithmetic units").
Timing normalize_units(NormalizeMode mode, const core::Settings& s) {
  const Timing add = unit(s, "add"), mul = unit(s, "mul"), div = unit(s, "div"), sqrt = unit(s, "sqrt"),
               table = unit(s, "rsqrt_table");
  const Timing radicand = mul + add + add;      // N·N: three products side by side, two sums
  const Timing newton = mul + mul + mul + add;  // y · (1.5 − 0.5·r·y²)
  switch (mode) {
    case NormalizeMode::Exact: return radicand + sqrt + div + mul;  // N · (1 / √r)
    case NormalizeMode::ForwardDifference: return add + sqrt + div + mul;  // r by one addition, then exact
    case NormalizeMode::Rsqrt0: return radicand + table + mul;
    case NormalizeMode::Rsqrt1: return radicand + table + newton + mul;
    default: return radicand + table + 2 * newton + mul;
  }
}

// The block's timing as the pipeline resolves it: its own latency and II, and its units'.
Timing resolved_timing(const BlockContext& ctx) {
  const Timing units = normalize_units(parse_normalize_mode(ctx.string("mode")), ctx.settings);
  return {uint64_t(ctx.integer("latency")) + units.latency, std::max(uint64_t(ctx.integer("ii")), units.ii), 0};
}
}  // namespace

BlockDecl normalize_block() {
  BlockDecl d{"normalize", {1, 1}, true,
              {{"mode", "exact", normalize_mode_names(), 0, 0, "how the normal is normalized"},
               {"seed", "packet", radicand_seed_names(), 0, 0,
                "forward-difference mode: the radicand seeded at every packet, or once per raster line and "
                "carried from packet to packet (docs/pipeline.md)"},
               {"impl", "kernel", {"kernel", "rtl"}, 0, 0,
                "the C++ kernel, or the RTL unit verilated into the loop (docs/rtl.md)"}},
              {},  // always: every shading path lights a unit normal
              [](const BlockContext& ctx) -> std::unique_ptr<Block> {
                const NormalizeMode mode = parse_normalize_mode(ctx.string("mode"));
                const bool per_line = ctx.string("seed") == "line";
                if (ctx.string("impl") == "rtl" && per_line && mode == NormalizeMode::ForwardDifference)
                  throw core::InputError(ctx.scene.file, "pipeline.normalize.seed",
                                         "line: the RTL unit (impl=rtl) seeds its radicand at every packet");
                if (ctx.string("impl") == "rtl")
                  return std::make_unique<SpanBlock<NormalizeRtlKernel>>(mode, ctx.format(), resolved_timing(ctx),
                                                                         ctx.scene.file);
                return std::make_unique<SpanBlock<NormalizeKernel>>(
                    mode, ctx.format(), per_line ? RadicandSeed::Line : RadicandSeed::Packet);
              }};
  d.units = [](const BlockContext& ctx) { return normalize_units(parse_normalize_mode(ctx.string("mode")), ctx.settings); };
  d.vectors = true;  // the words at the pins of rtl/normalize/normalize_unit.sv
  return d;
}

}  // namespace shadetlm::modules
