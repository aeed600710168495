// The raster's declaration (modules/common/declaration.hpp).
#include "shadetlm/modules/common/declaration.hpp"
#include "shadetlm/modules/raster/raster.hpp"

namespace shadetlm::modules {

namespace {
class RasterBlock : public Block {
 public:
  RasterBlock(int width, int height) : kernel_(width, height) {}
  Kind kind() const override { return Kind::Raster; }
  void emit_spans(const TriangleSetup& t, const std::function<void(SpanPacket&)>& emit) override {
    kernel_.run(t, emit);
  }
  std::unique_ptr<BlockInfo> module(const char* name, Timing timing, sc_core::sc_time period) override {
    return std::make_unique<Raster>(name, kernel_, timing, period);
  }
  std::vector<std::string> trace_names() const override { return Raster::trace_names(); }
  Ops ops() const override { return kernel_.ops(); }
  void finish(BlockReport&, RenderResult& r) override {
    r.pixels_walked = kernel_.pixels_walked();
    r.pixels_hidden = kernel_.pixels_hidden();
  }

 private:
  RasterKernel kernel_;
};
}  // namespace

BlockDecl raster_block() {
  return {"raster", {4, 1}, false, {}, {}, [](const BlockContext& ctx) -> std::unique_ptr<Block> {
            return std::make_unique<RasterBlock>(ctx.scene.camera.width, ctx.scene.camera.height);
          }};
}

}  // namespace shadetlm::modules
