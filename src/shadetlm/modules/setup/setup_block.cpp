// The setup block's declaration (tlm/block.hpp): the source of the
// main pass.
#include "shadetlm/tlm/block.hpp"
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
  // A triangle it drops costs the cycles to find out: snapping and the sign of the screen
  // determinant (2 mul, 1 add), which it computes first, before any plane.
  std::vector<core::SettingSpec> settings = {
      {"reject_cycles", 2, {}, 1, 1000000,
       "cycles setup's unit spends on a triangle it culls or clips away (docs/pipeline.md, Timing)"}};
  BlockDecl d{"setup", {16, 8}, false, settings, {}, [](const BlockContext& ctx) -> std::unique_ptr<Block> {
                // It sets up the planes the interpolators read: N or N/w as normal_interp
                // steps, L and V for affine bump vectors and H's planes as vector_interp reads them.
                auto block = std::make_unique<SetupBlock>(ctx.scene,
                                                          ctx.settings.string("normal_interp.mode") == "perspective",
                                                          ctx.settings.string("vector_interp.bump_vectors") == "affine",
                                                          ctx.settings.string("vector_interp.h") == "interpolated");
                block->kernel.reject_cycles = uint64_t(ctx.integer("reject_cycles"));
                return block;
              }};
  d.fifo = BlockDecl::Fifo::None;  // the source
  return d;
}

}  // namespace shadetlm::modules
