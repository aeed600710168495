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

BlockDecl texel_project_block() {
  BlockDecl d{"texel_project", {16, 1}, true,
              {{"units", 4, {}, 1, 64, "parallel splat units of texel_project"},
               {"accumulator_bits", 32, {}, 8, 64, "bits of each of a pixel's four accumulated numbers (DRAM model)"},
               {"lod", "most-magnified", {"most-magnified", "constant-z"}, 0, 0,
                "LOD rule: the spacing at the visible polygon's most magnified vertex, or the paper's constant z'"}},
              TexelProjectKernel::needed, [](const BlockContext& ctx) -> std::unique_ptr<Block> {
                std::optional<TexelProjectKernel::Memory> memory;
                if (const auto cache = cache_of(ctx)) {
                  const core::Settings& s = ctx.settings;
                  memory = TexelProjectKernel::Memory{
                      *cache,
                      DramTiming{uint64_t(s.integer("memory.latency")), uint64_t(s.integer("memory.bytes_per_cycle"))},
                      ctx.integer("accumulator_bits")};
                }
                const auto lod = ctx.string("lod") == "constant-z" ? TexelProjectKernel::Lod::ConstantZ
                                                                   : TexelProjectKernel::Lod::MostMagnified;
                return std::make_unique<TexelProjectBlock>(ctx.scene, ctx.integer("units"), ctx.format(), memory, lod);
              }};
  d.fifo = BlockDecl::Fifo::None;  // a pass of its own over the frame
  d.memory = true;                 // texel reads and splats through caches (docs/memory.md)
  return d;
}

}  // namespace shadetlm::modules
