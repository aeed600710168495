// The raster's declaration (tlm/block.hpp).
#include "shadetlm/tlm/block.hpp"
#include "shadetlm/modules/raster/raster.hpp"

namespace shadetlm::modules {

namespace {
class RasterBlock : public KernelBlock<RasterKernel, Raster> {
 public:
  using KernelBlock::KernelBlock;
  Kind kind() const override { return Kind::Raster; }
  std::vector<std::string> trace_names() const override { return Raster::trace_names(); }
  void emit_spans(const TriangleSetup& t, SpanChain& chain) override {
    kernel.run(t, chain);
    kernel.hidden_lines().clear();  // (the plain loop has no timing to give them)
  }
  void finish(BlockReport& b, RenderResult& r) override {
    r.pixels_walked = kernel.pixels_walked();
    r.pixels_hidden = kernel.pixels_hidden();
    if (const MemoryClient* m = kernel.memory())
      b.stats.memory = memory_stats(*m, b.stats.memory_stall_cycles);
  }
};
}  // namespace

BlockDecl raster_block() {
  BlockDecl d = declare("raster");
  d.basics.timing = {4, 1, 4};
  d.basics.fifo = BlockBasics::Fifo::Triangles;
  d.basics.memory = true;  // the depth buffer through a cache (docs/memory.md)
  d.make = [](const BlockContext& ctx) -> std::unique_ptr<Block> {
    return std::make_unique<RasterBlock>(ctx.scene.camera.width, ctx.scene.camera.height, cache_of(ctx));
  };
  return d;
}

}  // namespace shadetlm::modules
