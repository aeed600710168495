#pragma once
// The transaction timeline: one slice per packet per block (per triangle for setup),
// with the cycles its pixels stalled, and each block's FIFO occupancy as a counter,
// written as Chrome trace-event JSON, which Perfetto UI opens: one track per block, in
// pipeline order.
#include <cstdint>
#include <string>
#include <vector>

namespace shadetlm::modules {

class Timeline {
 public:
  struct Slice {
    uint32_t block;      // index into the names given to write()
    uint64_t start, busy;  // cycles
    uint32_t pixels, triangle;
    uint64_t stalled;      // cycles its pixels waited, done, for room downstream
  };
  struct Count {
    uint32_t block;
    uint64_t cycle;
    uint32_t fifo;  // pixels in the block's input FIFO
  };
  void add(uint32_t block, uint64_t start, uint64_t busy, uint32_t pixels, uint32_t triangle, uint64_t stalled = 0) {
    slices_.push_back({block, start, busy, pixels, triangle, stalled});
  }
  void count(uint32_t block, uint64_t cycle, uint32_t fifo) { counts_.push_back({block, cycle, fifo}); }
  // The DRAM's bytes per bin of `bin_cycles` up to cycle `end` (docs/memory.md): a
  // counter of its own.
  void set_dram(uint64_t bin_cycles, std::vector<uint64_t> bytes_per_bin, uint64_t end) {
    dram_bin_ = bin_cycles, dram_bytes_ = std::move(bytes_per_bin), dram_end_ = end;
  }
  const std::vector<Slice>& slices() const { return slices_; }
  // Writes the JSON (through a temporary and a rename); times in µs at `clock_mhz`.
  void write(const std::string& path, const std::vector<std::string>& block_names, double clock_mhz) const;

 private:
  std::vector<Slice> slices_;
  std::vector<Count> counts_;
  uint64_t dram_bin_ = 0, dram_end_ = 0;
  std::vector<uint64_t> dram_bytes_;
};

}  // namespace shadetlm::modules
