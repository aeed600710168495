#include "shadetlm/tlm/block.hpp"

#include <algorithm>
#include <stdexcept>

#include "shadetlm/core/input_error.hpp"

namespace shadetlm::modules {

std::vector<std::string> PipelineDecl::block_names() const {
  std::vector<std::string> names;
  for (const auto& pass : passes)
    for (const auto& b : pass.blocks) names.push_back(b.name);
  return names;
}

std::vector<core::SettingSpec> PipelineDecl::all_settings() const {
  std::vector<core::SettingSpec> all = settings;
  for (const auto& pass : passes)
    for (const auto& b : pass.blocks) {
      all.push_back({b.name + ".latency", b.timing.latency, {}, 1, 1000000,
                     "cycles from a pixel's start to its hand-over (docs/pipeline.md, Timing)"});
      all.push_back({b.name + ".ii", b.timing.ii, {}, 1, 1000000, "cycles per unit of work"});
      if (b.fifo != BlockDecl::Fifo::None)
        all.push_back({b.name + ".fifo_depth", b.timing.fifo_depth, {}, 1, 65536,
                       b.fifo == BlockDecl::Fifo::Triangles ? "triangles its input FIFO holds"
                                                             : "pixels its input FIFO holds"});
      if (b.memory) {
        // At most 16 MiB, 2^20 lines and 64 ways: a cache of silicon, and a model that
        // fits in memory and looks up a line in a few steps.
        all.push_back({b.name + ".cache.size", 16384, {}, 16, 1 << 24, "bytes of its cache (a power of two)"});
        all.push_back({b.name + ".cache.line", 64, {}, 16, 4096, "bytes of its cache's line (a power of two)"});
        all.push_back({b.name + ".cache.ways", 4, {}, 1, 64, "its cache's associativity (dividing its lines)"});
        all.push_back({b.name + ".cache.layout", "tiled", layout_names(), 0, 0,
                       "how its surfaces lie in memory: linear, tiled (a line a tile) or morton"});
        if (b.fifo != BlockDecl::Fifo::None)  // (a frame pass is timed as a whole)
          all.push_back({b.name + ".miss_queue", 64, {}, 0, 65536,
                         "pixels it may hold waiting for memory, besides its pipeline registers"});
      }
      if (b.formatted)
        all.push_back({b.name + ".format", "default", {}, 0, 0,
                       "number format of the block's datapath (default: pipeline.number_format)", true});
      for (core::SettingSpec s : b.settings) {
        s.key = b.name + "." + s.key;
        all.push_back(std::move(s));
      }
    }
  return all;
}

std::optional<CacheConfig> cache_of(const BlockContext& ctx) {
  if (ctx.settings.string("memory.model") == "ideal") return std::nullopt;
  CacheConfig c;
  c.size = uint64_t(ctx.integer("cache.size"));
  c.line = uint32_t(ctx.integer("cache.line"));
  c.ways = uint32_t(ctx.integer("cache.ways"));
  c.layout = parse_layout(ctx.string("cache.layout"));
  const CacheFault fault = check(c);
  if (!fault.setting.empty())
    throw core::InputError(ctx.scene.file, "pipeline." + ctx.name + ".cache." + fault.setting, fault.why);
  return c;
}

void PipelineDecl::insert_after(const std::string& after, BlockDecl block) {
  const auto names = block_names();
  if (std::find(names.begin(), names.end(), block.name) != names.end())
    throw std::invalid_argument("the pipeline has a block named " + block.name + " already");
  for (auto& pass : passes)
    for (auto it = pass.blocks.begin(); it != pass.blocks.end(); ++it)
      if (it->name == after) {
        pass.blocks.insert(it + 1, std::move(block));
        return;
      }
  throw std::invalid_argument("the pipeline has no block named " + after);
}

}  // namespace shadetlm::modules
