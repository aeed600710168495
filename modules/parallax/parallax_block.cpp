// The parallax tracer's declaration (modules/common/declaration.hpp).
#include "shadetlm/modules/common/declaration.hpp"
#include "shadetlm/modules/parallax/parallax_kernel.hpp"

namespace shadetlm::modules {

BlockDecl parallax_block() {
  return {"parallax", {16, 1}, true, {}, ParallaxKernel::needed, [](const BlockContext& ctx) -> std::unique_ptr<Block> {
            return std::make_unique<SpanBlock<ParallaxKernel>>(ctx.scene, ctx.format());
          }};
}

}  // namespace shadetlm::modules
