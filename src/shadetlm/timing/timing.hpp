#pragma once
// A block's timing as the scene sets it (`<block>.latency`, `.ii`, `.fifo_depth`;
// docs/pipeline.md, "Timing"), as the fast model (main_pass.hpp), the statistics and
// the timing log read it.
#include <cstdint>

namespace shadetlm::modules {

struct Timing {
  uint64_t latency = 1;     // cycles from a pixel's start to its hand-over, when nothing waits
  uint64_t ii = 1;          // cycles per unit of work (initiation interval)
  uint64_t fifo_depth = 8;  // pixels its input FIFO holds (triangles for the raster)
  // A memory client under the DRAM model (docs/memory.md): the bytes of its cache's line
  // (0: it moves nothing, or memory is ideal) and the pixels it may hold waiting for
  // memory besides its pipeline registers (its latency-hiding queue).
  uint64_t line_bytes = 0;
  uint64_t miss_queue = 0;
};

// The pixels a block may hold between starting them and handing them on:
// C = ⌈(L + 1) / II⌉ registers, and its miss queue under the memory model.
inline uint64_t capacity(const Timing& t) {
  return (t.latency + 1 + t.ii - 1) / t.ii + (t.line_bytes > 0 ? t.miss_queue : 0);
}

}  // namespace shadetlm::modules
