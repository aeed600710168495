#pragma once
// The transaction timeline: one slice per packet per block (per triangle for setup
// and raster), written as Chrome trace-event JSON, which Perfetto UI and
// chrome://tracing open: one track per block, in pipeline order.
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
  };
  void add(uint32_t block, uint64_t start, uint64_t busy, uint32_t pixels, uint32_t triangle) {
    slices_.push_back({block, start, busy, pixels, triangle});
  }
  const std::vector<Slice>& slices() const { return slices_; }
  // Writes the JSON (through a temporary and a rename); times in µs at `clock_mhz`.
  void write(const std::string& path, const std::vector<std::string>& block_names, double clock_mhz) const;

 private:
  std::vector<Slice> slices_;
};

}  // namespace shadetlm::modules
