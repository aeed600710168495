// The bump perturbation's declaration (modules/common/declaration.hpp).
#include "shadetlm/modules/bump_perturb/bump_perturb_kernel.hpp"
#include "shadetlm/modules/common/declaration.hpp"

namespace shadetlm::modules {

BlockDecl bump_perturb_block() {
  return {"bump_perturb", {8, 1}, false, {}, BumpPerturbKernel::needed,
          [](const BlockContext& ctx) -> std::unique_ptr<Block> {
            // It interpolates as the normal interpolator does (N or N/w).
            return std::make_unique<SpanBlock<BumpPerturbKernel>>(ctx.settings.string("normal_interp.mode") ==
                                                                  "perspective");
          }};
}

}  // namespace shadetlm::modules
