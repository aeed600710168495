// The setup block's declaration (modules/common/declaration.hpp): the source of the
// main pass.
#include "shadetlm/modules/common/declaration.hpp"
#include "shadetlm/modules/setup/setup.hpp"

namespace shadetlm::modules {

namespace {
class SetupBlock : public Block {
 public:
  SetupBlock(const core::Scene& scene, bool perspective, bool affine_bump_vectors)
      : kernel_(scene, perspective, affine_bump_vectors) {}
  Kind kind() const override { return Kind::Source; }
  void emit_triangles(const std::function<void(const TriangleSetup&)>& emit) override { kernel_.run(emit); }
  void set_progress(std::function<void(double)> progress) override { kernel_.set_progress(std::move(progress)); }
  std::unique_ptr<BlockInfo> module(const char* name, Timing timing, sc_core::sc_time period) override {
    return std::make_unique<Setup>(name, kernel_, timing, period);
  }
  Ops ops() const override { return kernel_.ops(); }
  void finish(BlockReport&, RenderResult& r) override {
    r.triangles_in = kernel_.triangles_in();
    r.triangles_drawn = kernel_.triangles_out();
  }

 private:
  SetupKernel kernel_;
};
}  // namespace

BlockDecl setup_block() {
  return {"setup", {16, 8}, false, {}, {}, [](const BlockContext& ctx) -> std::unique_ptr<Block> {
            // It sets up the planes the interpolators read: N or N/w as normal_interp
            // steps, L and V for affine bump vectors as vector_interp reads them.
            return std::make_unique<SetupBlock>(ctx.scene, ctx.settings.string("normal_interp.mode") == "perspective",
                                                ctx.settings.string("vector_interp.bump_vectors") == "affine");
          }};
}

}  // namespace shadetlm::modules
