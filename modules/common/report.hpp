#pragma once
// What a render reports: per block and for the frame (the stats JSON, docs/pipeline.md).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "shadetlm/core/frame.hpp"
#include "shadetlm/modules/common/number.hpp"
#include "shadetlm/modules/common/ops.hpp"
#include "shadetlm/modules/common/range.hpp"

namespace shadetlm::modules {

// A block's timing (modules/common/timing.hpp).
struct Timing {
  uint64_t latency = 1;     // cycles from a pixel's start to its hand-over, when nothing waits
  uint64_t ii = 1;          // cycles per unit of work (initiation interval)
  uint64_t fifo_depth = 8;  // pixels its input FIFO holds (triangles for the raster)
};

struct BlockStats {
  uint64_t packets = 0, pixels = 0, busy_cycles = 0, bypassed = 0;
  uint64_t starved_cycles = 0, blocked_cycles = 0;  // waiting for input, for room downstream
  uint64_t fifo_cycles = 0, fifo_peak = 0;          // Σ pixel-cycles in its input FIFO; the most it held
  bool fifo_measured = false;                       // a FIFO of pixels before it, measured
  Ops ops;
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
  std::string timing_log;           // Inspect::timing_log: the main pass's times (modules/common/timing.hpp)
  double precompute_s = 0;          // maps built when the pipeline was (not in wall_s)
  uint64_t nonfinite_replaced = 0;   // NaN or infinite colour, normal, depth or specular values that reached the framebuffer (replaced)

  const BlockReport* bottleneck() const;  // the block with the most busy cycles
  Ops total_ops() const;
  nlohmann::json stats_json() const;
};

}  // namespace shadetlm::modules
