// The setup block's declaration (modules/common/declaration.hpp): the source of the
// main pass.
#include "shadetlm/modules/common/declaration.hpp"
#include "shadetlm/modules/setup/setup.hpp"

namespace shadetlm::modules {

namespace {
class SetupBlock : public KernelBlock<SetupKernel, Setup> {
 public:
  using KernelBlock::KernelBlock;
  Kind kind() const override { return Kind::Source; }
  void run_pass(Block& raster, SpanChain& chain) override {
    kernel.run([&](const TriangleSetup& t) { raster.emit_spans(t, chain); });
  }
  void set_progress(std::function<void(double)> progress) override { kernel.set_progress(std::move(progress)); }
  void finish(BlockReport&, RenderResult& r) override {
    r.triangles_in = kernel.triangles_in();
    r.triangles_drawn = kernel.triangles_out();
  }
};
}  // namespace

BlockDecl setup_block() {
  BlockDecl d{"setup", {16, 8}, false, {}, {}, [](const BlockContext& ctx) -> std::unique_ptr<Block> {
                // It sets up the planes the interpolators read: N or N/w as normal_interp
                // steps, L and V for affine bump vectors and H's planes as vector_interp reads them.
                return std::make_unique<SetupBlock>(ctx.scene,
                                                    ctx.settings.string("normal_interp.mode") == "perspective",
                                                    ctx.settings.string("vector_interp.bump_vectors") == "affine",
                                                    ctx.settings.string("vector_interp.h") == "interpolated");
              }};
  d.fifo = BlockDecl::Fifo::None;  // the source
  return d;
}

}  // namespace shadetlm::modules
