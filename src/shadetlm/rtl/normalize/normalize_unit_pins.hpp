#pragma once
// The RTL normalize unit (normalize_unit.sv, verilated) as the clocked timing
// reference's unit for the normalize block (timing_reference::UnitPins; docs/rtl.md,
// "In lockstep"): `shadetlm timing-check LOG --rtl-normalize MODE`.
#include <cstdint>
#include <memory>
#include <string>

#include "shadetlm/timing_reference/clocked.hpp"

namespace shadetlm::rtl {

// The unit of mode `mode` (0 … 4, in the order of pipeline.normalize.mode's values);
// with `vcd` not empty, its pins and registers are traced to that file, a nanosecond a
// cycle (the reference's clock). Throws std::invalid_argument if this build has no RTL.
std::unique_ptr<timing_reference::UnitPins> make_normalize_unit_pins(int mode, const std::string& vcd);

// The latency and II the unit of mode `mode` was built with (rtl/CMakeLists.txt).
struct UnitTiming {
  int64_t latency, ii;
};
UnitTiming normalize_unit_timing(int mode);

}  // namespace shadetlm::rtl
