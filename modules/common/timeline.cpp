#include "shadetlm/modules/common/timeline.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "shadetlm/core/frame.hpp"

namespace shadetlm::modules {

void Timeline::write(const std::string& path, const std::vector<std::string>& names, double clock_mhz) const {
  std::ostringstream out;
  {
    out.precision(12);
    out << "{\"displayTimeUnit\": \"ns\", \"traceEvents\": [\n";
    // Track names, in pipeline order.
    for (size_t b = 0; b < names.size(); ++b)
      out << "{\"ph\": \"M\", \"pid\": 1, \"tid\": " << b << ", \"name\": \"thread_name\", \"args\": {\"name\": \""
          << names[b] << "\"}},\n{\"ph\": \"M\", \"pid\": 1, \"tid\": " << b
          << ", \"name\": \"thread_sort_index\", \"args\": {\"sort_index\": " << b << "}},\n";
    out << "{\"ph\": \"M\", \"pid\": 1, \"name\": \"process_name\", \"args\": {\"name\": \"shadetlm pipeline\"}}";
    for (const auto& s : slices_)
      out << ",\n{\"ph\": \"X\", \"pid\": 1, \"tid\": " << s.block << ", \"name\": \"" << names[s.block]
          << "\", \"ts\": " << double(s.start) / clock_mhz << ", \"dur\": " << double(s.busy) / clock_mhz
          << ", \"args\": {\"pixels\": " << s.pixels << ", \"cycles\": " << s.busy << ", \"start_cycle\": "
          << s.start << ", \"triangle\": " << s.triangle << ", \"stalled_cycles\": " << s.stalled << "}}";
    for (const auto& c : counts_)
      out << ",\n{\"ph\": \"C\", \"pid\": 1, \"name\": \"" << names[c.block] << " FIFO\", \"ts\": "
          << double(c.cycle) / clock_mhz << ", \"args\": {\"pixels\": " << c.fifo << "}}";
    for (size_t k = 0; k < dram_bytes_.size(); ++k) {  // bytes a cycle over each bin (the last one's part)
      const uint64_t from = k * dram_bin_, length = std::max<uint64_t>(std::min(dram_bin_, dram_end_ - std::min(dram_end_, from)), 1);
      out << ",\n{\"ph\": \"C\", \"pid\": 1, \"name\": \"DRAM bandwidth\", \"ts\": " << double(from) / clock_mhz
          << ", \"args\": {\"bytes_per_cycle\": " << double(dram_bytes_[k]) / double(length) << ", \"cycles\": " << length
          << "}}";
    }
    out << "\n]}\n";
  }
  core::write_file(path, out.str());
}

}  // namespace shadetlm::modules
