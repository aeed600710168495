#pragma once
// The clocked timing reference (docs/pipeline.md, "The timing check"): the main pass
// as SystemC modules that step every clock — setup, the raster's walker and each span
// block — joined by valid/ready handshakes into FIFOs of the configured depths, one
// pixel per handshake. It reads the kernels' work per pixel (a Workload) and none of the
// fast model's timing code: it is to cycles what reference/ is to colour.
#include <cstdint>
#include <string>
#include <vector>

#include "shadetlm/timing_reference/workload.hpp"

namespace shadetlm::timing_reference {

struct Measured {
  std::vector<std::vector<int64_t>> start, valid, handed;  // [raster, span blocks…][pixel]
  std::vector<int64_t> setup_start, setup_handed, taken;  // per triangle
  std::vector<BlockStatsLine> stats;                      // setup, the raster, the span blocks
  int64_t end = 0;       // the first cycle at which every block is done
  bool finished = false; // false: stopped at the cycle bound (a deadlock)
  double wall_s = 0;
};

// Elaborates the clocked model of `w` and runs it to the end (once per process:
// SystemC elaborates once).
Measured run_clocked(const Workload& w);

// The fast model's times in `w` against the clocked ones: every mismatch counted, the
// first `show` described in `report`. True if all are equal.
bool compare(const Workload& w, const Measured& m, std::string& report, size_t show = 10);

}  // namespace shadetlm::timing_reference
