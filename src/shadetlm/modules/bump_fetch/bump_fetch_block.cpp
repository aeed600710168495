// The bump fetch's declaration (tlm/block.hpp).
#include "shadetlm/modules/bump_fetch/bump_fetch_kernel.hpp"
#include "shadetlm/tlm/block.hpp"

namespace shadetlm::modules {

// Its own settings, pipeline.bump_fetch.<key>.
// Its fields are the kernel's options (their defaults the kernel's), and how the texture
// memory stores a texel, which the kernel takes as bits.
struct BumpFetchSettings {
  static constexpr const char* block = "bump_fetch";
  BumpFetchKernel::Options options;
  enum class Stored { Float, Unorm8, Unorm10, Unorm16 } stored = Stored::Float;

  template <class F>
  void fields(F& f) {
    const std::vector<std::string> filters(filter_names().begin(), filter_names().begin() + 4);  // no EWA
    f(options.filter, "filter", filters,
      "texture filter of the bump fetch (nearest and bilinear on the nearest mip level)");
    f(options.probes, "probes", {1, 16}, "anisotropic filter: trilinear probes along the footprint's major axis");
    f(options.renormalize_mips, "renormalize_mips",
      "normal maps built on load: renormalize the texels of every mip level");
    f(stored, "stored", {"float", "unorm8", "unorm10", "unorm16"},
      "the normal maps' texels as the texture memory holds them: float, or (N + 1) / 2 in 8, 10 or 16 bits a "
      "component (docs/bump-mapping.md)");
  }
};

BlockDecl bump_fetch_block() {
  BlockDecl d = declare<BumpFetchSettings>();
  d.basics.timing = {24, 1};
  d.basics.formatted = true;
  d.basics.memory = true;  // reads its maps through a cache (docs/memory.md)
  d.needed = BumpFetchKernel::needed;
  d.make = [](const BlockContext& ctx) -> std::unique_ptr<Block> {
    const BumpFetchSettings s = ctx.read<BumpFetchSettings>();
    BumpFetchKernel::Options o = s.options;
    o.cache = cache_of(ctx);
    const int bits[] = {0, 8, 10, 16};
    o.stored_bits = bits[int(s.stored)];
    return std::make_unique<SpanBlock<BumpFetchKernel>>(ctx.scene, o, ctx.format());
  };
  return d;
}

}  // namespace shadetlm::modules
