// The parallax tracer's declaration (tlm/block.hpp).
#include "shadetlm/tlm/block.hpp"
#include "shadetlm/modules/parallax/parallax_kernel.hpp"

namespace shadetlm::modules {

int64_t parallax_cell_cycles(const PipelineSettings::Units& u) {
  // An exact cell test (18 mul, 2 div, a square root, four texels): the tracer has one
  // divider and one square root unit, so a test takes the divider twice
  // (docs/configuration.md, "Arithmetic units").
  return int64_t(std::max(2 * u.div.ii, u.sqrt.ii));
}

BlockDecl parallax_block() {
  BlockDecl d = declare("parallax");
  d.basics.timing = {16, 1};
  d.basics.formatted = true;
  d.basics.memory = true;  // reads its maps through a cache (docs/memory.md)
  d.needed = ParallaxKernel::needed;
  d.make = [](const BlockContext& ctx) -> std::unique_ptr<Block> {
    return std::make_unique<SpanBlock<ParallaxKernel>>(ctx.scene, ctx.format(), parallax_cell_cycles(ctx.pipeline.unit),
                                                       cache_of(ctx));
  };
  return d;
}

}  // namespace shadetlm::modules
