// The bump perturbation's declaration (tlm/block.hpp).
#include "shadetlm/modules/bump_perturb/bump_perturb_kernel.hpp"
#include "shadetlm/tlm/block.hpp"
#include "shadetlm/modules/normal_interp/normal_interp_settings.hpp"

namespace shadetlm::modules {

BlockDecl bump_perturb_block() {
  BlockDecl d = declare("bump_perturb");
  d.basics.timing = {1, 1};
  d.basics.formatted = true;
  d.needed = BumpPerturbKernel::needed;
  d.make = [](const BlockContext& ctx) -> std::unique_ptr<Block> {
    // It interpolates as the normal interpolator does (N or N/w).
    return std::make_unique<SpanBlock<BumpPerturbKernel>>(ctx.read<NormalInterpSettings>().perspective(), ctx.format());
  };
  // The critical path of N' = c·N + Fu (n × Pv) + Fv (Pu × n): a plane stepped (add),
  // times w (mul), times Fu (mul), two sums (docs/configuration.md, "Arithmetic units").
  d.units = [](const BlockContext& ctx) {
    const PipelineSettings::Units& u = ctx.pipeline.unit;
    return u.add + u.mul + u.mul + u.add + u.add;
  };
  return d;
}

}  // namespace shadetlm::modules
