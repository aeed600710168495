#pragma once
// The shared DRAM of the fast timing model (docs/memory.md): a latency and a bandwidth
// of B bytes a cycle, shared by every memory client of the main pass, oldest pixel
// first. In each cycle it moves up to B bytes, to the requests present in the order of
// their pixels (and, for one pixel, of the blocks along the pipeline); a request made
// in cycle s is present from cycle s + 1, and its data is back `latency` cycles after
// the cycle of its last byte.
//
// Oldest-first means a request never waits for a younger one: the fast model places
// requests in its pixel-major order (that order) on a calendar of the bytes each cycle
// has left, each taking what the older ones left — which is what the clocked reference's
// arbiter, deciding cycle by cycle, gives it. The calendar keeps runs of full cycles and
// the cycles taken in part, so that a long request (a wide line at a byte a cycle) costs
// a few steps, not one a cycle.
#include <cstdint>
#include <map>
#include <vector>

namespace shadetlm::modules {

struct DramTiming {
  uint64_t latency = 200;          // cycles from a request's last byte to its data in the block
  uint64_t bytes_per_cycle = 32;
};

class Dram {
 public:
  explicit Dram(DramTiming t);
  // A request of `bytes` (> 0) made in cycle `made`: returns the cycle its data is back.
  int64_t request(int64_t made, uint64_t bytes);
  // No request will be made before cycle `cycle` any more: the calendar forgets it.
  void forget_before(int64_t cycle);
  uint64_t bytes() const { return bytes_; }
  const DramTiming& timing() const { return timing_; }
  // Bytes moved per bin of `bin_cycles` (0: not kept), for the bandwidth over time.
  void keep_histogram(uint64_t bin_cycles) { bin_cycles_ = bin_cycles; }
  const std::vector<uint64_t>& bytes_per_bin() const { return per_bin_; }

 private:
  void fill(int64_t from, int64_t to);           // cycles [from, to) taken in full
  void count(int64_t cycle, uint64_t bytes, int64_t cycles = 1);  // the histogram
  DramTiming timing_;
  std::map<int64_t, int64_t> full_;     // runs of full cycles: first → one past the last (apart, not adjacent)
  std::map<int64_t, uint64_t> part_;    // cycles taken in part: cycle → bytes taken
  int64_t base_ = 0;                    // no request is made before it
  uint64_t bytes_ = 0;
  uint64_t bin_cycles_ = 0;
  std::vector<uint64_t> per_bin_;
};

}  // namespace shadetlm::modules
