#include "modules/common/block.hpp"

#include <algorithm>

namespace modules {

Block::Block(sc_core::sc_module_name name, Timing timing, sc_core::sc_time clock_period)
    : sc_core::sc_module(name), in("in"), out("out"), timing_(timing), period_(clock_period) {
  in.register_b_transport(this, &Block::transport);
}

uint64_t Block::occupy(uint64_t arrival, uint64_t busy) {
  const uint64_t start = std::max(arrival, free_);
  free_ = start + busy;
  stats_.busy_cycles += busy;
  return start + timing_.latency;
}

void Block::forward(tlm::tlm_generic_payload& trans, uint64_t cycle) {
  if (!has_next()) return;
  // The annotation is relative to the caller's local time: never negative, because
  // a packet's cycle only grows along the pipeline and the source keeps local time.
  const sc_core::sc_time at = period_ * double(cycle);
  sc_core::sc_time delay = at > sc_core::sc_time_stamp() ? at - sc_core::sc_time_stamp() : sc_core::SC_ZERO_TIME;
  out->b_transport(trans, delay);
}

}  // namespace modules
