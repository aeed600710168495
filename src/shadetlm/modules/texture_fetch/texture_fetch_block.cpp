// The colour texture fetch's declaration (tlm/block.hpp).
#include "shadetlm/tlm/block.hpp"
#include "shadetlm/modules/texture_fetch/texture_fetch_kernel.hpp"

namespace shadetlm::modules {

// Its own settings, pipeline.texture_fetch.<key>.
// Its fields are the kernel's options (their defaults the kernel's), read as they are.
struct TextureFetchSettings {
  static constexpr const char* block = "texture_fetch";
  TextureFetchKernel::Options options;

  template <class F>
  void fields(F& f) {
    f(options.filter, "filter", filter_names(), "screen-space filter of texture-screen materials");
    f(options.probes, "probes", {1, 16}, "anisotropic filter: trilinear probes along the footprint's major axis");
  }
};

BlockDecl texture_fetch_block() {
  BlockDecl d = declare<TextureFetchSettings>();
  d.basics.timing = {8, 1};
  d.basics.memory = true;  // reads its maps through a cache (docs/memory.md)
  d.needed = TextureFetchKernel::needed;
  d.make = [](const BlockContext& ctx) -> std::unique_ptr<Block> {
    TextureFetchKernel::Options o = ctx.read<TextureFetchSettings>().options;
    o.cache = cache_of(ctx);
    return std::make_unique<SpanBlock<TextureFetchKernel>>(ctx.scene, o);
  };
  return d;
}

}  // namespace shadetlm::modules
