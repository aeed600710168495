#include "shadetlm/memory/dram.hpp"

#include <algorithm>
#include <limits>

namespace shadetlm::modules {

Dram::Dram(DramTiming t) : timing_(t) {}

void Dram::fill(int64_t from, int64_t to) {
  auto next = full_.lower_bound(from);
  if (next != full_.begin()) {  // a run ending at `from`: extend it
    auto before = std::prev(next);
    if (before->second == from) from = before->first, full_.erase(before);
  }
  if (next != full_.end() && next->first == to) to = next->second, full_.erase(next);
  full_[from] = to;
}

void Dram::count(int64_t cycle, uint64_t bytes, int64_t cycles) {
  if (bin_cycles_ == 0 || bytes == 0) return;
  for (int64_t t = cycle, end = cycle + cycles; t < end;) {
    const uint64_t bin = uint64_t(t) / bin_cycles_;
    const int64_t until = std::min<int64_t>(end, int64_t((bin + 1) * bin_cycles_));
    if (per_bin_.size() <= bin) per_bin_.resize(bin + 1, 0);
    per_bin_[bin] += bytes * uint64_t(until - t);
    t = until;
  }
}

int64_t Dram::request(int64_t made, uint64_t bytes) {
  bytes_ += bytes;
  const uint64_t per_cycle = timing_.bytes_per_cycle;
  const int64_t never = std::numeric_limits<int64_t>::max();
  int64_t t = std::max(made + 1, base_);
  for (;;) {
    auto run = full_.upper_bound(t);  // over a run of full cycles
    if (run != full_.begin() && std::prev(run)->second > t) t = std::prev(run)->second, run = full_.upper_bound(t);
    if (auto part = part_.find(t); part != part_.end()) {  // what the older requests left of cycle t
      const uint64_t take = std::min(per_cycle - part->second, bytes);
      part->second += take, bytes -= take;
      count(t, take);
      if (part->second == per_cycle) part_.erase(part), fill(t, t + 1);
      if (bytes == 0) return t + int64_t(timing_.latency);
      ++t;
      continue;
    }
    // Free cycles up to the next one taken: whole ones, then what is left in part.
    const auto next_part = part_.upper_bound(t);
    const int64_t free_until = std::min(run != full_.end() ? run->first : never,
                                        next_part != part_.end() ? next_part->first : never);
    const int64_t whole = int64_t(std::min<uint64_t>(bytes / per_cycle, uint64_t(free_until - t)));
    if (whole > 0) {
      fill(t, t + whole);
      count(t, per_cycle, whole);
      bytes -= uint64_t(whole) * per_cycle, t += whole;
      if (bytes == 0) return t - 1 + int64_t(timing_.latency);
      continue;
    }
    part_[t] = bytes;  // less than a cycle's bytes, into a free cycle
    count(t, bytes);
    return t + int64_t(timing_.latency);
  }
}

void Dram::forget_before(int64_t cycle) {
  if (cycle <= base_) return;
  base_ = cycle;
  while (!full_.empty() && full_.begin()->second <= cycle) full_.erase(full_.begin());
  while (!part_.empty() && part_.begin()->first < cycle) part_.erase(part_.begin());
}

}  // namespace shadetlm::modules
