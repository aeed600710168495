// The framebuffer's declaration (tlm/block.hpp).
#include "shadetlm/tlm/block.hpp"
#include "shadetlm/modules/framebuffer/framebuffer_kernel.hpp"

namespace shadetlm::modules {

namespace {
class FramebufferBlock : public SpanBlock<FramebufferKernel> {
 public:
  using SpanBlock::SpanBlock;
  void finish(BlockReport& b, RenderResult& r) override {
    SpanBlock::finish(b, r);
    r.nonfinite_replaced = kernel.nonfinite();
    r.frame = std::move(kernel.frame());
  }
};

bool has_texture_object(const core::Scene& scene) {
  for (const auto& o : scene.objects)
    if (scene.materials[size_t(o.material)].path == core::ShadingPath::TextureObject) return true;
  return false;
}
}  // namespace

BlockDecl framebuffer_block() {
  BlockDecl d = declare("framebuffer");
  d.basics.timing = {2, 1};
  d.basics.memory = true;  // writes colour through a cache (docs/memory.md)
  d.make = [](const BlockContext& ctx) -> std::unique_ptr<Block> {
    // Texture-object materials are resolved by a later pass over the frame: keep what it
    // needs (the visible triangle and specular term per pixel).
    return std::make_unique<FramebufferBlock>(ctx.scene, has_texture_object(ctx.scene), cache_of(ctx));
  };
  return d;
}

}  // namespace shadetlm::modules
