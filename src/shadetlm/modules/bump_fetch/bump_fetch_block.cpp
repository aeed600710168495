// The bump fetch's declaration (tlm/block.hpp).
#include "shadetlm/modules/bump_fetch/bump_fetch_kernel.hpp"
#include "shadetlm/tlm/block.hpp"

namespace shadetlm::modules {

BlockDecl bump_fetch_block() {
  const std::vector<std::string> filters(filter_names().begin(), filter_names().begin() + 4);  // no EWA
  BlockDecl d{"bump_fetch", {24, 1}, true,
          {{"filter", "trilinear", filters, 0, 0,
            "texture filter of the bump fetch (nearest and bilinear on the nearest mip level)"},
           {"probes", 4, {}, 1, 16, "anisotropic filter: trilinear probes along the footprint's major axis"},
           {"renormalize_mips", true, {}, 0, 0, "normal maps built on load: renormalize the texels of every mip level"},
           {"stored", "float", {"float", "unorm8", "unorm10", "unorm16"}, 0, 0,
            "the normal maps' texels as the texture memory holds them: float, or (N + 1) / 2 in 8, 10 or 16 bits "
            "a component (docs/bump-mapping.md)"}},
          BumpFetchKernel::needed,
          [](const BlockContext& ctx) -> std::unique_ptr<Block> {
            BumpFetchKernel::Options o;
            o.filter = parse_filter(ctx.string("filter"));
            o.probes = ctx.integer("probes");
            o.cache = cache_of(ctx);
            o.renormalize_mips = ctx.boolean("renormalize_mips");
            const std::string stored = ctx.string("stored");
            o.stored_bits = stored == "float" ? 0 : std::stoi(stored.substr(5));
            return std::make_unique<SpanBlock<BumpFetchKernel>>(ctx.scene, o, ctx.format());
          }};
  d.memory = true;  // reads its maps through a cache (docs/memory.md)
  return d;
}

}  // namespace shadetlm::modules
