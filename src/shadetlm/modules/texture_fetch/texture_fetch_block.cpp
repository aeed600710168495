// The colour texture fetch's declaration (tlm/block.hpp).
#include "shadetlm/tlm/block.hpp"
#include "shadetlm/modules/texture_fetch/texture_fetch_kernel.hpp"

namespace shadetlm::modules {

BlockDecl texture_fetch_block() {
  BlockDecl d{"texture_fetch", {8, 1}, false,
          {{"filter", "trilinear", filter_names(), 0, 0, "screen-space filter of texture-screen materials"},
           {"probes", 4, {}, 1, 16, "anisotropic filter: trilinear probes along the footprint's major axis"}},
          TextureFetchKernel::needed,
          [](const BlockContext& ctx) -> std::unique_ptr<Block> {
            TextureFetchKernel::Options o;
            o.filter = parse_filter(ctx.string("filter"));
            o.probes = ctx.integer("probes");
            o.cache = cache_of(ctx);
            return std::make_unique<SpanBlock<TextureFetchKernel>>(ctx.scene, o);
          }};
  d.memory = true;  // reads its maps through a cache (docs/memory.md)
  return d;
}

}  // namespace shadetlm::modules
