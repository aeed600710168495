// texel_project's declaration (modules/common/declaration.hpp): a pass of its own over
// the frame, after the main chain.
#include "shadetlm/modules/common/declaration.hpp"
#include "shadetlm/modules/texel_project/texel_project.hpp"

namespace shadetlm::modules {

namespace {
class TexelProjectBlock : public Block {
 public:
  TexelProjectBlock(const core::Scene& scene, int units, core::NumberFormat format) : kernel_(scene, units, format) {}
  Kind kind() const override { return Kind::Frame; }
  void end_pass(PassEnd& e) override {
    if (e.framebuffer) kernel_.run(*e.framebuffer);
  }
  std::unique_ptr<BlockInfo> module(const char* name, Timing timing, sc_core::sc_time period) override {
    return std::make_unique<TexelProject>(name, kernel_, timing, period);
  }
  Ops ops() const override { return kernel_.ops(); }
  void finish(BlockReport& b, RenderResult&) override {
    b.details = kernel_.details();
    b.numbers = kernel_.numbers();
  }

 private:
  TexelProjectKernel kernel_;
};
}  // namespace

BlockDecl texel_project_block() {
  return {"texel_project", {16, 1}, true, {{"units", 4, {}, 1, 64, "parallel splat units of texel_project"}},
          TexelProjectKernel::needed, [](const BlockContext& ctx) -> std::unique_ptr<Block> {
            return std::make_unique<TexelProjectBlock>(ctx.scene, ctx.integer("units"), ctx.format());
          }};
}

}  // namespace shadetlm::modules
