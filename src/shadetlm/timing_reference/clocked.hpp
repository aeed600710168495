#pragma once
// The clocked timing reference (docs/pipeline.md, "The timing check"): the main pass
// as SystemC modules that step every clock — setup, the raster's walker and each span
// block — joined by valid/ready handshakes into FIFOs of the configured depths, one
// pixel per handshake. It reads the kernels' work per pixel (a Workload) and none of the
// fast model's timing code: it is to cycles what reference/ is to colour.
#include <cstdint>
#include <string>
#include <vector>

#include <systemc>

#include "shadetlm/timing_reference/workload.hpp"

namespace shadetlm::timing_reference {

struct Measured {
  std::vector<std::vector<int64_t>> start, valid, handed;  // [raster, span blocks…][pixel]
  std::vector<int64_t> setup_start, setup_handed, taken;  // per triangle
  std::vector<BlockStatsLine> stats;                      // setup, the raster, the span blocks
  int64_t main_end = 0;  // the first cycle at which every block of the main pass is done
  struct Pass {
    int64_t arrival = -1, busy = 0, last = -1;
  };
  std::vector<Pass> passes;  // the frame passes' (Workload::passes)
  int64_t end = 0;       // the first cycle at which every block of every pass is done
  bool finished = false; // false: stopped at the cycle bound (a deadlock)
  double wall_s = 0;
  std::string pins_block;  // a span block whose unit was pins (UnitPins): its busy, starved and blocked not kept
};

// A span block's unit at the pins (docs/rtl.md, "In lockstep"): an RTL model of what
// follows the block's input FIFO — issue, pipeline, output register — clocked by the
// reference's clock in place of the reference's own unit, joined to the FIFO before it
// and the link after it by valid/ready handshakes. Items are the workload's pixels.
class UnitPins {
 public:
  virtual ~UnitPins() = default;
  // Binds the unit's clock, and its output handshake and item to the next block's input.
  virtual void bind(sc_core::sc_signal_in_if<bool>& clk, sc_core::sc_signal<bool>& out_valid,
                    sc_core::sc_signal<bool>& out_ready, sc_core::sc_signal<int64_t>& out_item) = 0;
  // The input for the next cycle: `item` offered or not, the first of its packet.
  virtual void offer(bool valid, int64_t item, bool first) = 0;
  virtual bool in_ready() const = 0;  // this cycle's
};

// Elaborates the clocked model of `w` and runs it to the end (once per process:
// SystemC elaborates once). With `pins`, the span block named `pins_block` has them as
// its unit.
Measured run_clocked(const Workload& w, const std::string& pins_block = {}, UnitPins* pins = nullptr);

// The fast model's times in `w` against the clocked ones: every mismatch counted, the
// first `show` described in `report`. True if all are equal.
bool compare(const Workload& w, const Measured& m, std::string& report, size_t show = 10);

}  // namespace shadetlm::timing_reference
