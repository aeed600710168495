#include "shadetlm/modules/common/block.hpp"

namespace shadetlm::modules {

void Schedule::histogram(uint64_t start, uint64_t busy) {
  for (uint64_t t = start, end = start + busy; t < end;) {
    const uint64_t bin = t / bin_cycles_, bin_end = (bin + 1) * bin_cycles_;
    if (bins_.size() <= bin) bins_.resize(bin + 1, 0);
    const uint64_t until = std::min(end, bin_end);
    bins_[bin] += until - t;
    t = until;
  }
}

}  // namespace shadetlm::modules
