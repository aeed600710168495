// The setup block's declaration (tlm/block.hpp): the source of the
// main pass.
#include "shadetlm/tlm/block.hpp"
#include "shadetlm/modules/setup/setup.hpp"
#include "shadetlm/modules/normal_interp/normal_interp_settings.hpp"
#include "shadetlm/modules/vector_interp/vector_interp_settings.hpp"

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

// Its own setting, pipeline.setup.<key>.
struct SetupSettings {
  static constexpr const char* block = "setup";
  // A triangle it drops costs the cycles to find out: snapping and the sign of the screen
  // determinant (2 mul, 1 add), which it computes first, before any plane.
  uint64_t reject_cycles = 2;
  template <class F>
  void fields(F& f) {
    f(reject_cycles, "reject_cycles", {1, 1000000},
      "cycles setup's unit spends on a triangle it culls or clips away (docs/pipeline.md, Timing)");
  }
};

BlockDecl setup_block() {
  BlockDecl d = declare<SetupSettings>();
  d.basics.timing = {16, 8};
  d.basics.fifo = BlockBasics::Fifo::None;  // the source
  d.make = [](const BlockContext& ctx) -> std::unique_ptr<Block> {
    // It sets up the planes the interpolators read: N or N/w as normal_interp steps, L
    // and V for affine bump vectors and H's planes as vector_interp reads them.
    const NormalInterpSettings normals = ctx.read<NormalInterpSettings>();
    const VectorInterpSettings vectors = ctx.read<VectorInterpSettings>();
    auto block = std::make_unique<SetupBlock>(ctx.scene, normals.perspective(), vectors.affine_bump_vectors(),
                                              vectors.interpolate_h());
    block->kernel.reject_cycles = ctx.read<SetupSettings>().reject_cycles;
    return block;
  };
  return d;
}

}  // namespace shadetlm::modules
