// The parallax tracer's declaration (modules/common/declaration.hpp).
#include "shadetlm/modules/common/declaration.hpp"
#include "shadetlm/modules/parallax/parallax_kernel.hpp"

namespace shadetlm::modules {

BlockDecl parallax_block() {
  BlockDecl d{"parallax", {16, 1}, true, {}, ParallaxKernel::needed, [](const BlockContext& ctx) -> std::unique_ptr<Block> {
            // An exact cell test (18 mul, 2 div, a square root, four texels): the tracer
            // has one divider and one square root unit, so a test takes the divider twice
            // (docs/configuration.md, "Arithmetic units").
            const Timing div = unit(ctx.settings, "div"), sqrt = unit(ctx.settings, "sqrt");
            const int64_t cell_cycles = int64_t(std::max(2 * div.ii, sqrt.ii));
            return std::make_unique<SpanBlock<ParallaxKernel>>(ctx.scene, ctx.format(), cell_cycles, cache_of(ctx));
          }};
  d.memory = true;  // reads its maps through a cache (docs/memory.md)
  return d;
}

}  // namespace shadetlm::modules
