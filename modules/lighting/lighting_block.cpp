// The lighting block's declaration (modules/common/declaration.hpp).
#include "shadetlm/modules/common/declaration.hpp"
#include "shadetlm/modules/lighting/lighting_kernel.hpp"

namespace shadetlm::modules {

BlockDecl lighting_block() {
  return {"lighting", {10, 1}, true, {}, {}, [](const BlockContext& ctx) -> std::unique_ptr<Block> {
            return std::make_unique<SpanBlock<LightingKernel>>(ctx.scene, ctx.format());
          }};
}

}  // namespace shadetlm::modules
