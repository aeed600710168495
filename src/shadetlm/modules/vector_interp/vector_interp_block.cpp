// The L and H interpolator's declaration (tlm/block.hpp).
#include "shadetlm/tlm/block.hpp"
#include "shadetlm/modules/vector_interp/vector_interp_kernel.hpp"
#include "shadetlm/modules/vector_interp/vector_interp_settings.hpp"

namespace shadetlm::modules {

BlockDecl vector_interp_block() {
  BlockDecl d = declare<VectorInterpSettings>();
  d.basics.timing = {20, 1};
  d.basics.formatted = true;
  d.needed = VectorInterpKernel::needed;
  d.make = [](const BlockContext& ctx) -> std::unique_ptr<Block> {
    const VectorInterpSettings s = ctx.read<VectorInterpSettings>();
    return std::make_unique<SpanBlock<VectorInterpKernel>>(ctx.scene, point_lights(ctx.scene), s.affine_bump_vectors(),
                                                           ctx.format(), s.interpolate_h());
  };
  return d;
}

}  // namespace shadetlm::modules
