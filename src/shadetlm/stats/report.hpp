#pragma once
// What a render reports: per block and for the frame (the stats JSON, docs/pipeline.md).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "shadetlm/core/frame.hpp"
#include "shadetlm/numeric/number.hpp"
#include "shadetlm/numeric/ops.hpp"
#include "shadetlm/numeric/range.hpp"
#include "shadetlm/memory/cache.hpp"
#include "shadetlm/memory/dram.hpp"
#include "shadetlm/timing/timing.hpp"

namespace shadetlm::modules {

// A memory client's figures under the DRAM model (docs/memory.md).
struct MemoryStats {
  CacheConfig cache;
  Cache::Counts counts;
  uint64_t flushed = 0;       // dirty lines written back at the frame's end
  uint64_t stall_cycles = 0;  // Σ over its pixels of the cycles their data came after their work
  uint64_t other_bytes = 0;   // through another cache of the block (texel_project's accumulators)
  uint64_t dram_bytes() const { return (counts.misses + counts.writebacks + flushed) * cache.line + other_bytes; }
};
// A client's figures from its port: what its cache counted, and what is dirty at the
// frame's end (written back then); `stall_cycles` from the timing.
inline MemoryStats memory_stats(const MemoryClient& m, uint64_t stall_cycles) {
  return {m.cache().config(), m.cache().counts(), m.cache().dirty_lines(), stall_cycles};
}

struct BlockStats {
  uint64_t packets = 0, pixels = 0, busy_cycles = 0, bypassed = 0;
  uint64_t starved_cycles = 0, blocked_cycles = 0;  // waiting for input, for room downstream
  uint64_t fifo_cycles = 0, fifo_peak = 0;          // Σ pixel-cycles in its input FIFO; the most it held
  bool fifo_measured = false;                       // a FIFO of pixels before it, measured
  Ops ops;
  std::optional<MemoryStats> memory;                // a memory client under the DRAM model
  uint64_t memory_stall_cycles = 0;                 // the timing's (MemoryStats::stall_cycles)
};

struct BlockReport {
  std::string name;
  BlockStats stats;
  Timing timing;
  int64_t last_cycle = -1;  // when it handed on its last result
  std::vector<uint64_t> busy_per_bin;  // busy cycles per Inspect::bin_cycles
  Ranges ranges;                       // of the block's datapaths (docs/pipeline.md)
  nlohmann::json details;              // block-specific figures (texel_project)
  std::optional<NumberStats> numbers;  // its number format and what its numbers met
};

struct RenderResult {
  core::Frame frame;
  std::string engine;  // "systemc" or "loop"
  double wall_s = 0;
  double clock_mhz = 0;
  uint64_t frame_cycles = 0;  // 0 for the loop, which has no timing model
  uint64_t triangles_in = 0, triangles_drawn = 0;
  uint64_t pixels_walked = 0, pixels_hidden = 0, pixels_shaded = 0;
  std::vector<BlockReport> blocks;  // elaborated blocks, in pipeline order
  uint64_t bin_cycles = 0;          // of the blocks' busy_per_bin (0: none)
  uint64_t trace_records = 0;       // pixels written to the VCD, all blocks
  uint64_t vector_pixels = 0;       // pixels written as test vectors, all blocks
  std::string timing_log;           // Inspect::timing_log: the main pass's times (timing/main_pass.hpp)
  double precompute_s = 0;          // maps built when the pipeline was (not in wall_s)
  std::optional<DramTiming> dram;   // the DRAM model's (none: ideal memory)
  std::vector<uint64_t> dram_bytes_per_bin;  // its bytes per bin_cycles (kept with bin_cycles)
  uint64_t nonfinite_replaced = 0;   // NaN or infinite colour, normal, depth or specular values that reached the framebuffer (replaced)

  const BlockReport* bottleneck() const;  // the block with the most busy cycles
  Ops total_ops() const;
  nlohmann::json stats_json() const;
  nlohmann::json silicon_json(nlohmann::json& blocks_json) const;  // (stats_json's "silicon")
};

}  // namespace shadetlm::modules
