// The bump perturbation's declaration (tlm/block.hpp).
#include "shadetlm/modules/bump_perturb/bump_perturb_kernel.hpp"
#include "shadetlm/tlm/block.hpp"

namespace shadetlm::modules {

BlockDecl bump_perturb_block() {
  BlockDecl d{"bump_perturb", {1, 1}, true, {}, BumpPerturbKernel::needed,
              [](const BlockContext& ctx) -> std::unique_ptr<Block> {
                // It interpolates as the normal interpolator does (N or N/w).
                return std::make_unique<SpanBlock<BumpPerturbKernel>>(
                    ctx.settings.string("normal_interp.mode") == "perspective", ctx.format());
              }};
  // The critical path of N' = c·N + Fu (n × Pv) + Fv (Pu × n): a plane stepped (add),
  // times w (mul), times Fu (mul), two sums (docs/configuration.md, "Arithmetic units").
  d.units = [](const BlockContext& ctx) {
    const Timing add = unit(ctx.settings, "add"), mul = unit(ctx.settings, "mul");
    return add + mul + mul + add + add;
  };
  return d;
}

}  // namespace shadetlm::modules
