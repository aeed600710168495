// The normal interpolator's declaration (tlm/block.hpp).
#include "shadetlm/tlm/block.hpp"
#include "shadetlm/modules/normal_interp/normal_interp_kernel.hpp"
#include "shadetlm/modules/normal_interp/normal_interp_settings.hpp"

namespace shadetlm::modules {

BlockDecl normal_interp_block() {
  BlockDecl d = declare<NormalInterpSettings>();
  d.basics.timing = {2, 1};
  d.basics.formatted = true;
  d.make = [](const BlockContext& ctx) -> std::unique_ptr<Block> {
    return std::make_unique<SpanBlock<NormalInterpKernel>>(ctx.read<NormalInterpSettings>().reseed_interval(),
                                                           ctx.format());
  };
  return d;
}

}  // namespace shadetlm::modules
