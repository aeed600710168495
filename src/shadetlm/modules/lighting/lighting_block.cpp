// The lighting block's declaration (tlm/block.hpp).
#include "shadetlm/tlm/block.hpp"
#include "shadetlm/modules/lighting/lighting_kernel.hpp"

namespace shadetlm::modules {

BlockDecl lighting_block() {
  BlockDecl d = declare("lighting");
  d.basics.timing = {1, 1};
  d.basics.formatted = true;
  d.make = [](const BlockContext& ctx) -> std::unique_ptr<Block> {
    return std::make_unique<SpanBlock<LightingKernel>>(ctx.scene, ctx.format());
  };
  // A light's critical path: N·H (three products, two sums; N·L alongside), the power
  // 2^(e·log2 x), the colour scaled and summed (docs/configuration.md).
  d.units = [](const BlockContext& ctx) {
    const PipelineSettings::Units& u = ctx.pipeline.unit;
    return u.mul + u.add + u.add + u.log2 + u.mul + u.exp2 + u.mul + u.add;
  };
  return d;
}

}  // namespace shadetlm::modules
