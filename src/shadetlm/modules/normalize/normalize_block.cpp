// The normalize block's declaration (tlm/block.hpp).
#include "shadetlm/core/input_error.hpp"
#include "shadetlm/tlm/block.hpp"
#include "shadetlm/modules/normalize/normalize_kernel.hpp"
#include "shadetlm/modules/normalize/normalize_rtl.hpp"
#include "shadetlm/modules/normalize/normalize_settings.hpp"

namespace shadetlm::modules {

namespace {
// Each mode's critical path, unit after unit (docs/configuration.md, "Arithmetic units").
Timing normalize_units(NormalizeMode mode, const PipelineSettings::Units& u) {
  const Timing radicand = u.mul + u.add + u.add;      // N·N: three products side by side, two sums
  const Timing newton = u.mul + u.mul + u.mul + u.add;  // y · (1.5 − 0.5·r·y²)
  switch (mode) {
    case NormalizeMode::Exact: return radicand + u.sqrt + u.div + u.mul;  // N · (1 / √r)
    case NormalizeMode::ForwardDifference: return u.add + u.sqrt + u.div + u.mul;  // r by one addition, then exact
    case NormalizeMode::Rsqrt0: return radicand + u.rsqrt_table + u.mul;
    case NormalizeMode::Rsqrt1: return radicand + u.rsqrt_table + newton + u.mul;
    default: return radicand + u.rsqrt_table + 2 * newton + u.mul;
  }
}

// The block's timing as the pipeline resolves it: its own latency and II, and its units'.
Timing resolved_timing(const BlockContext& ctx, NormalizeMode mode) {
  const Timing units = normalize_units(mode, ctx.pipeline.unit);
  return {ctx.basics.timing.latency + units.latency, std::max(ctx.basics.timing.ii, units.ii), 0};
}
}  // namespace

BlockDecl normalize_block() {
  BlockDecl d = declare<NormalizeSettings>();
  d.basics.timing = {1, 1};
  d.basics.formatted = true;
  // (always needed: every shading path lights a unit normal)
  d.make = [](const BlockContext& ctx) -> std::unique_ptr<Block> {
    const NormalizeSettings s = ctx.read<NormalizeSettings>();
    const bool rtl = s.impl == NormalizeSettings::Impl::Rtl;
    if (rtl && s.seed == RadicandSeed::Line && s.mode == NormalizeMode::ForwardDifference)
      throw core::InputError(ctx.scene.file, "pipeline.normalize.seed",
                             "line: the RTL unit (impl=rtl) seeds its radicand at every packet");
    if (rtl)
      return std::make_unique<SpanBlock<NormalizeRtlKernel>>(s.mode, ctx.format(), resolved_timing(ctx, s.mode),
                                                             ctx.scene.file);
    return std::make_unique<SpanBlock<NormalizeKernel>>(s.mode, ctx.format(), s.seed);
  };
  d.units = [](const BlockContext& ctx) { return normalize_units(ctx.read<NormalizeSettings>().mode, ctx.pipeline.unit); };
  d.vectors = true;  // the words at the pins of rtl/normalize/normalize_unit.sv
  return d;
}

}  // namespace shadetlm::modules
