// The raster's declaration (modules/common/declaration.hpp).
#include "shadetlm/modules/common/declaration.hpp"
#include "shadetlm/modules/raster/raster.hpp"

namespace shadetlm::modules {

namespace {
class RasterBlock : public KernelBlock<RasterKernel, Raster> {
 public:
  using KernelBlock::KernelBlock;
  Kind kind() const override { return Kind::Raster; }
  void emit_spans(const TriangleSetup& t, SpanChain& chain) override { kernel.run(t, chain); }
  std::vector<std::string> trace_names() const override { return Raster::trace_names(); }
  void finish(BlockReport&, RenderResult& r) override {
    r.pixels_walked = kernel.pixels_walked();
    r.pixels_hidden = kernel.pixels_hidden();
  }
};
}  // namespace

BlockDecl raster_block() {
  BlockDecl d{"raster", {4, 1, 4}, false, {}, {}, [](const BlockContext& ctx) -> std::unique_ptr<Block> {
                return std::make_unique<RasterBlock>(ctx.scene.camera.width, ctx.scene.camera.height);
              }};
  d.fifo = BlockDecl::Fifo::Triangles;
  return d;
}

}  // namespace shadetlm::modules
