// The normalize block's declaration (modules/common/declaration.hpp).
#include "shadetlm/modules/common/declaration.hpp"
#include "shadetlm/modules/normalize/normalize_kernel.hpp"

namespace shadetlm::modules {

BlockDecl normalize_block() {
  return {"normalize", {12, 1}, true,
          {{"mode", "exact", normalize_mode_names(), 0, 0, "how the normal is normalized"}},
          {},  // always: every shading path lights a unit normal
          [](const BlockContext& ctx) -> std::unique_ptr<Block> {
            return std::make_unique<SpanBlock<NormalizeKernel>>(parse_normalize_mode(ctx.string("mode")), ctx.format());
          }};
}

}  // namespace shadetlm::modules
