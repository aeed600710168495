// The L and H interpolator's declaration (tlm/block.hpp).
#include "shadetlm/tlm/block.hpp"
#include "shadetlm/modules/vector_interp/vector_interp_kernel.hpp"

namespace shadetlm::modules {

BlockDecl vector_interp_block() {
  return {"vector_interp", {20, 1}, true,
          {{"bump_vectors", "unit", {"unit", "affine"}, 0, 0,
            "fetched-normal bump paths: interpolate unit L and H (the paper's) or L and V as affine vectors"},
           {"h", "pixel", {"pixel", "interpolated"}, 0, 0,
            "world-space paths: H = normalize(L + V) of the unit L and V at each pixel, or H at the vertices "
            "interpolated and normalized (Fig. 1 of the bump-mapping paper)"}},
          VectorInterpKernel::needed,
          [](const BlockContext& ctx) -> std::unique_ptr<Block> {
            return std::make_unique<SpanBlock<VectorInterpKernel>>(ctx.scene, point_lights(ctx.scene),
                                                                   ctx.string("bump_vectors") == "affine", ctx.format(),
                                                                   ctx.string("h") == "interpolated");
          }};
}

}  // namespace shadetlm::modules
