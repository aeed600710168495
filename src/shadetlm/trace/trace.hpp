#pragma once
// Waveforms of the blocks (docs/inspecting.md). A block with a probe records, for each
// pixel of a traced region, its outputs from the cycle the timing model puts them at
// its output to the cycle it hands them on; after the run the Tracer writes the records
// in time order as a VCD, so that it shows each block's valid, ready (low while the next
// FIFO is full: a stall), x, y, triangle and values at the pixels' simulated times.
// Outside the region a block pays one test per packet. (The VCD is written here, not by
// SystemC's writer: that one writes in place, unchecked, and costs a string time stamp
// per time step.)
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <systemc>

#include "shadetlm/core/output.hpp"

namespace shadetlm::modules {

// False in a build configured with -DSHADETLM_TRACING=OFF: the blocks' tracing hooks
// compile away (used only to measure their cost).
#ifdef SHADETLM_NO_TRACING
constexpr bool kTracing = false;
#else
constexpr bool kTracing = true;
#endif

struct TraceRegion {
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;  // inclusive pixel bounds; empty: nothing traced
  uint32_t triangle_first = 0, triangle_last = UINT32_MAX;
  bool covers(int y, int x_begin, int x_end, uint32_t triangle) const {
    return y >= y0 && y <= y1 && x_end > x0 && x_begin <= x1 && triangle >= triangle_first &&
           triangle <= triangle_last;
  }
  bool contains(int x, int y) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1; }
};

class Tracer {
 public:
  Tracer(TraceRegion region, sc_core::sc_time period);

  // During elaboration: a block's signals (valid, ready, x, y, triangle, then `values`).
  int add_probe(const std::string& block, const std::vector<std::string>& values);
  const TraceRegion& region() const { return region_; }
  // A pixel at a block's output (values in the order of add_probe): valid from cycle
  // `valid`, handed on at `handed` (ready high then; low before it: a stall).
  void record(int probe, uint64_t valid, uint64_t handed, int x, int y, uint32_t triangle, const double* values);
  // After the run: the records as a VCD, written to its temporary in `outputs`, the
  // run's outputs that appear together (core/output.hpp).
  void write_vcd(core::OutputSet& outputs, const std::string& path);  // (sorts the records)

  // The signals, for the GTKWave save file: (block, full VCD names).
  struct ProbeInfo {
    std::string block;
    std::vector<std::string> names;  // "shadetlm.raster.valid", …
    std::vector<bool> is_real;
  };
  const std::vector<ProbeInfo>& probes() const { return info_; }
  uint64_t records() const { return records_; }
  uint64_t first_cycle() const { return first_; }  // of the records (0 if none)
  uint64_t last_cycle() const { return last_; }

 private:
  static constexpr int kMaxValues = 8;  // per probe
  struct Record {  // a pixel at a probe's output
    uint64_t valid, handed;
    int probe, x, y;
    uint32_t triangle;
    std::array<double, kMaxValues> values;
  };
  // A change of a probe's signals, for the VCD: at `cycle`, by `kind`: 0 clears valid
  // and ready, 1 sets a record's pixel (after a clear at the same cycle), 2 sets ready.
  struct Event {
    uint64_t cycle;
    uint32_t kind, record;  // (record: also the order among equals)
    bool operator<(const Event& o) const {
      if (cycle != o.cycle) return cycle < o.cycle;
      if (kind != o.kind) return kind < o.kind;
      return record < o.record;
    }
  };

  TraceRegion region_;
  sc_core::sc_time period_;
  std::vector<size_t> value_count_;  // per probe
  std::vector<ProbeInfo> info_;
  std::vector<Record> records_list_;  // in the order recorded
  uint64_t records_ = 0, first_ = 0, last_ = 0;
};

}  // namespace shadetlm::modules
