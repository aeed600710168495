// The L and H interpolator's declaration (modules/common/declaration.hpp).
#include "shadetlm/modules/common/declaration.hpp"
#include "shadetlm/modules/vector_interp/vector_interp_kernel.hpp"

namespace shadetlm::modules {

BlockDecl vector_interp_block() {
  return {"vector_interp", {20, 1}, true,
          {{"bump_vectors", "unit", {"unit", "affine"}, 0, 0,
            "fetched-normal bump paths: interpolate unit L and H (the paper's) or L and V as affine vectors"}},
          VectorInterpKernel::needed,
          [](const BlockContext& ctx) -> std::unique_ptr<Block> {
            return std::make_unique<SpanBlock<VectorInterpKernel>>(ctx.scene, point_lights(ctx.scene),
                                                                   ctx.string("bump_vectors") == "affine", ctx.format());
          }};
}

}  // namespace shadetlm::modules
