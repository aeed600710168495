#pragma once
// The SystemC side shared by every block: a TLM-2.0 target socket in, an initiator
// socket out, and the timing and cost bookkeeping.
//
// Timing model (docs/pipeline.md): each block has a latency L and an initiation
// interval II (cycles per pixel, or per triangle for setup). Blocks are joined by
// unbounded queues: a packet arriving at cycle t starts at max(t, the block's free
// cycle), keeps the block busy for II·pixels cycles, and reaches the next block L
// cycles after it started. Arrival cycles travel in the packet; the b_transport delay
// annotation carries the same time, relative to the initiator's local time.
#include <cstdint>
#include <string>

#include <systemc>
#include <tlm>
#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/simple_target_socket.h>

#include "modules/common/ops.hpp"

namespace modules {

struct Timing {
  uint64_t latency = 1;  // cycles from a packet's start to its first result downstream
  uint64_t ii = 1;       // cycles per pixel (initiation interval)
};

struct BlockStats {
  uint64_t packets = 0, pixels = 0, busy_cycles = 0, bypassed = 0;
  Ops ops;
};

class Block : public sc_core::sc_module {
 public:
  tlm_utils::simple_target_socket<Block> in;
  tlm_utils::simple_initiator_socket_optional<Block> out;  // unbound at the last block

  Block(sc_core::sc_module_name name, Timing timing, sc_core::sc_time clock_period);

  const BlockStats& stats() const { return stats_; }
  const Timing& timing() const { return timing_; }
  uint64_t free_cycle() const { return free_; }  // when the block finishes its last packet
  bool has_next() const { return out.size() > 0; }

 protected:
  // Books `busy` cycles for work arriving at `arrival`; returns when its first result
  // reaches the next block.
  uint64_t occupy(uint64_t arrival, uint64_t busy);
  // Sends a transaction to the next block, with the delay annotation of `cycle`.
  void forward(tlm::tlm_generic_payload& trans, uint64_t cycle);

  BlockStats stats_;

 private:
  virtual void b_transport(tlm::tlm_generic_payload& trans, sc_core::sc_time& delay) = 0;
  void transport(tlm::tlm_generic_payload& trans, sc_core::sc_time& delay) { b_transport(trans, delay); }

  Timing timing_;
  sc_core::sc_time period_;
  uint64_t free_ = 0;
};

}  // namespace modules
