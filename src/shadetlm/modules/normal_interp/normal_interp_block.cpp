// The normal interpolator's declaration (tlm/block.hpp).
#include "shadetlm/tlm/block.hpp"
#include "shadetlm/modules/normal_interp/normal_interp_kernel.hpp"

namespace shadetlm::modules {

namespace {
// normal_interp.reseed: 0 none, −1 per line, N every N pixels.
int reseed_interval(const std::string& name) {
  return name == "none" ? 0 : name == "line" ? -1 : std::stoi(name.substr(4));  // tileN
}
}  // namespace

BlockDecl normal_interp_block() {
  return {"normal_interp", {2, 1}, true,
          {{"mode", "perspective", {"affine", "perspective"}, 0, 0,
            "constant increments of N (affine) or of N/w and 1/w (perspective)"},
           {"reseed", "none", {"none", "line", "tile8", "tile16", "tile32"}, 0, 0,
            "walk the whole triangle from its seed, or take every row start (and every 8, 16, 32 pixels) from the "
            "plane"}},
          {},
          [](const BlockContext& ctx) -> std::unique_ptr<Block> {
            return std::make_unique<SpanBlock<NormalInterpKernel>>(reseed_interval(ctx.string("reseed")), ctx.format());
          }};
}

}  // namespace shadetlm::modules
