// The bump fetch's declaration (tlm/block.hpp).
#include "shadetlm/modules/bump_fetch/bump_fetch_kernel.hpp"
#include "shadetlm/tlm/block.hpp"

namespace shadetlm::modules {

// Its own settings, pipeline.bump_fetch.<key>.
struct BumpFetchSettings {
  static constexpr const char* block = "bump_fetch";
  Filter filter = Filter::Trilinear;
  int probes = 4;
  bool renormalize_mips = true;
  enum class Stored { Float, Unorm8, Unorm10, Unorm16 } stored = Stored::Float;

  template <class F>
  void fields(F& f) {
    const std::vector<std::string> filters(filter_names().begin(), filter_names().begin() + 4);  // no EWA
    f(filter, "filter", filters, "texture filter of the bump fetch (nearest and bilinear on the nearest mip level)");
    f(probes, "probes", {1, 16}, "anisotropic filter: trilinear probes along the footprint's major axis");
    f(renormalize_mips, "renormalize_mips", "normal maps built on load: renormalize the texels of every mip level");
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
    BumpFetchKernel::Options o;
    o.filter = s.filter;
    o.probes = s.probes;
    o.cache = cache_of(ctx);
    o.renormalize_mips = s.renormalize_mips;
    const int bits[] = {0, 8, 10, 16};
    o.stored_bits = bits[int(s.stored)];
    return std::make_unique<SpanBlock<BumpFetchKernel>>(ctx.scene, o, ctx.format());
  };
  return d;
}

}  // namespace shadetlm::modules
