// texel_project's declaration (modules/common/declaration.hpp): a pass of its own over
// the frame, after the main chain.
#include "shadetlm/modules/common/declaration.hpp"
#include "shadetlm/modules/texel_project/texel_project.hpp"

namespace shadetlm::modules {

namespace {
class TexelProjectBlock : public KernelBlock<TexelProjectKernel, TexelProject> {
 public:
  using KernelBlock::KernelBlock;
  Kind kind() const override { return Kind::Frame; }
  void end_pass(PassEnd& e) override {
    if (e.framebuffer) kernel.run(*e.framebuffer);
  }
  void finish(BlockReport& b, RenderResult&) override {
    b.details = kernel.details();
    b.numbers = kernel.numbers();
  }
};
}  // namespace

BlockDecl texel_project_block() {
  BlockDecl d{"texel_project", {16, 1}, true, {{"units", 4, {}, 1, 64, "parallel splat units of texel_project"}},
              TexelProjectKernel::needed, [](const BlockContext& ctx) -> std::unique_ptr<Block> {
                return std::make_unique<TexelProjectBlock>(ctx.scene, ctx.integer("units"), ctx.format());
              }};
  d.fifo = BlockDecl::Fifo::None;  // a pass of its own over the frame
  return d;
}

}  // namespace shadetlm::modules
