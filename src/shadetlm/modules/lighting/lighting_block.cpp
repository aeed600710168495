// The lighting block's declaration (tlm/block.hpp).
#include "shadetlm/tlm/block.hpp"
#include "shadetlm/modules/lighting/lighting_kernel.hpp"

namespace shadetlm::modules {

BlockDecl lighting_block() {
  BlockDecl d{"lighting", {1, 1}, true, {}, {}, [](const BlockContext& ctx) -> std::unique_ptr<Block> {
                return std::make_unique<SpanBlock<LightingKernel>>(ctx.scene, ctx.format());
              }};
  // A light's critical path: N·H (three products, two sums; N·L alongside), the power
  // 2^(e·log2 x), the colour scaled and summed (docs/configuration.md).
  d.units = [](const BlockContext& ctx) {
    const Timing add = unit(ctx.settings, "add"), mul = unit(ctx.settings, "mul");
    return mul + add + add + unit(ctx.settings, "log2") + mul + unit(ctx.settings, "exp2") + mul + add;
  };
  return d;
}

}  // namespace shadetlm::modules
