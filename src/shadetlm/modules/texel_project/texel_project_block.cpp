// texel_project's declaration (tlm/block.hpp): a pass of its own over
// the frame, after the main chain.
#include "shadetlm/tlm/block.hpp"
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
    if (const MemoryClient* m = kernel.memory()) {  // texel reads; the accumulators' bytes besides
      b.stats.memory = memory_stats(*m, 0);
      b.stats.memory->other_bytes = kernel.accumulator_bytes();
      b.details["accumulator_dram_bytes"] = kernel.accumulator_bytes();
    }
  }
};
}  // namespace

// Its own settings, pipeline.texel_project.<key>.
struct TexelProjectSettings {
  static constexpr const char* block = "texel_project";
  int units = 4;
  int accumulator_bits = 32;
  TexelProjectKernel::Lod lod = TexelProjectKernel::Lod::MostMagnified;

  template <class F>
  void fields(F& f) {
    f(units, "units", {1, 64}, "parallel splat units of texel_project");
    f(accumulator_bits, "accumulator_bits", {8, 64}, "bits of each of a pixel's four accumulated numbers (DRAM model)");
    f(lod, "lod", {"most-magnified", "constant-z"},
      "LOD rule: the spacing at the visible polygon's most magnified vertex, or the paper's constant z'");
  }
};

BlockDecl texel_project_block() {
  BlockDecl d = declare<TexelProjectSettings>();
  d.basics.timing = {16, 1};
  d.basics.formatted = true;
  d.basics.fifo = BlockBasics::Fifo::None;  // a pass of its own over the frame
  d.basics.memory = true;                   // texel reads and splats through caches (docs/memory.md)
  d.needed = TexelProjectKernel::needed;
  d.make = [](const BlockContext& ctx) -> std::unique_ptr<Block> {
    const TexelProjectSettings s = ctx.read<TexelProjectSettings>();
    std::optional<TexelProjectKernel::Memory> memory;
    if (const auto cache = cache_of(ctx)) memory = TexelProjectKernel::Memory{*cache, ctx.pipeline.dram, s.accumulator_bits};
    return std::make_unique<TexelProjectBlock>(ctx.scene, s.units, ctx.format(), memory, s.lod);
  };
  return d;
}

}  // namespace shadetlm::modules
