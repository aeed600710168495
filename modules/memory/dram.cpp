#include "shadetlm/modules/memory/dram.hpp"

#include <algorithm>

namespace shadetlm::modules {

Dram::Dram(DramTiming t) : timing_(t), taken_(1024, 0), mask_(1023) {}

uint32_t& Dram::at(int64_t cycle) {
  const uint64_t offset = uint64_t(cycle - base_);
  if (offset >= taken_.size()) {  // grow the ring, keeping each cycle's bytes
    size_t size = taken_.size();
    while (size <= offset) size *= 2;
    std::vector<uint32_t> grown(size, 0);
    for (uint64_t k = 0; k < taken_.size(); ++k) grown[k] = taken_[(uint64_t(base_) + k) & mask_];
    // Re-based at base_ mod the new size, so that cycle c sits at c & mask.
    std::vector<uint32_t> placed(size, 0);
    for (uint64_t k = 0; k < size; ++k) placed[(uint64_t(base_) + k) & (size - 1)] = grown[k];
    taken_.swap(placed);
    mask_ = size - 1;
  }
  return taken_[uint64_t(cycle) & mask_];
}

int64_t Dram::request(int64_t made, uint64_t bytes) {
  bytes_ += bytes;
  const uint64_t per_cycle = timing_.bytes_per_cycle;
  int64_t t = std::max(made + 1, base_);
  for (;; ++t) {
    uint32_t& taken = at(t);
    const uint64_t take = std::min<uint64_t>(per_cycle - taken, bytes);
    taken += uint32_t(take);
    if (bin_cycles_ > 0 && take > 0) {
      const uint64_t bin = uint64_t(t) / bin_cycles_;
      if (per_bin_.size() <= bin) per_bin_.resize(bin + 1, 0);
      per_bin_[bin] += take;
    }
    bytes -= take;
    if (bytes == 0) return t + int64_t(timing_.latency);
  }
}

void Dram::forget_before(int64_t cycle) {
  if (cycle <= base_) return;
  const int64_t until = std::min<int64_t>(cycle, base_ + int64_t(taken_.size()));
  for (int64_t c = base_; c < until; ++c) taken_[uint64_t(c) & mask_] = 0;
  base_ = cycle;
}

}  // namespace shadetlm::modules
