#pragma once
// Waveforms of the blocks (docs/inspecting.md). A block with a probe records, for each
// pixel of a traced region, its outputs from the cycle the timing model puts them at
// its output to the cycle it hands them on; the Tracer replays the records in time
// order into variables written with sc_trace, so a VCD shows each block's valid, ready
// (low while the next FIFO is full: a stall), x, y, triangle and values at the pixels'
// simulated times. Outside the region a block pays one test per packet.
#include <array>
#include <cstdint>
#include <memory>
#include <queue>
#include <string>
#include <vector>

#include <systemc>

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

class Tracer : public sc_core::sc_module {
 public:
  SC_HAS_PROCESS(Tracer);
  Tracer(sc_core::sc_module_name name, const std::string& vcd_path, TraceRegion region,
         sc_core::sc_time period);
  ~Tracer() override;

  // During elaboration: a block's signals (valid, x, y, triangle, then `values`).
  int add_probe(const std::string& block, const std::vector<std::string>& values);
  const TraceRegion& region() const { return region_; }
  // A pixel at a block's output (values in the order of add_probe): valid from cycle
  // `valid`, handed on at `handed` (ready high then; low before it: a stall).
  void record(int probe, uint64_t valid, uint64_t handed, int x, int y, uint32_t triangle, const double* values);
  // The source has sent its last transaction: stop once the records are replayed.
  void source_done();

  // The signals, for the GTKWave save file: (block, full VCD names).
  struct ProbeInfo {
    std::string block;
    std::vector<std::string> names;  // "SystemC.shadetlm.raster.valid", …
    std::vector<bool> is_real;
  };
  const std::vector<ProbeInfo>& probes() const { return info_; }
  uint64_t records() const { return records_; }
  uint64_t first_cycle() const { return first_; }  // of the records (0 if none)
  uint64_t last_cycle() const { return last_; }

 private:
  struct Probe {
    bool valid = false, ready = false;
    int x = 0, y = 0;
    unsigned triangle = 0;
    std::vector<double> values;
  };
  static constexpr int kMaxValues = 8;  // per probe
  struct Event {
    uint64_t cycle;
    int kind;  // 0 clears valid and ready, 1 sets a pixel (clears first at the same cycle), 2 sets ready
    uint64_t seq;
    int probe, x, y;
    uint32_t triangle;
    std::array<double, kMaxValues> values;
    bool operator>(const Event& o) const {
      if (cycle != o.cycle) return cycle > o.cycle;
      if (kind != o.kind) return kind > o.kind;
      return seq > o.seq;
    }
  };
  void run();

  sc_core::sc_trace_file* file_;
  TraceRegion region_;
  sc_core::sc_time period_;
  std::vector<std::unique_ptr<Probe>> probes_;
  std::vector<ProbeInfo> info_;
  std::priority_queue<Event, std::vector<Event>, std::greater<Event>> queue_;
  sc_core::sc_event wake_;
  bool source_done_ = false;
  uint64_t next_wake_ = UINT64_MAX;  // the cycle the replay thread waits for
  bool end_ = false;  // "shadetlm.end_of_trace": rises a little after the last record
  uint64_t seq_ = 0, records_ = 0, first_ = 0, last_ = 0;
};

}  // namespace shadetlm::modules
