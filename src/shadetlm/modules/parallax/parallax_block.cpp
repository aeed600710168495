// The parallax tracer's declaration (tlm/block.hpp).
#include "shadetlm/tlm/block.hpp"
#include "shadetlm/modules/parallax/parallax_kernel.hpp"

namespace shadetlm::modules {

int64_t parallax_cell_cycles(const core::Settings& settings) {
  // An exact cell test (18 mul, 2 div, a square root, four texels): the tracer has one
  // divider and one square root unit, so a test takes the divider twice
  // (docs/configuration.md, "Arithmetic units").
  const Timing div = unit(settings, "div"), sqrt = unit(settings, "sqrt");
  return int64_t(std::max(2 * div.ii, sqrt.ii));
}

BlockDecl parallax_block() {
  BlockDecl d{"parallax", {16, 1}, true, {}, ParallaxKernel::needed, [](const BlockContext& ctx) -> std::unique_ptr<Block> {
            const int64_t cell_cycles = parallax_cell_cycles(ctx.settings);
            return std::make_unique<SpanBlock<ParallaxKernel>>(ctx.scene, ctx.format(), cell_cycles, cache_of(ctx));
          }};
  d.memory = true;  // reads its maps through a cache (docs/memory.md)
  return d;
}

}  // namespace shadetlm::modules
