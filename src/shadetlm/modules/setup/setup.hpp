#pragma once
// The setup block, the head of the pipeline: a SystemC thread that sets up each
// triangle (SetupKernel) and sends it on as one transaction. It holds the pipeline's
// one quantum keeper: local time advances by II cycles per triangle and the thread
// yields to the kernel only when a quantum is used up. A triangle is handed on when
// the raster's triangle FIFO has room (TriangleLine): the raster says, as it returns
// the transaction, the cycle it took the triangle. After the last triangle it sends
// the end of the pass (PassEnd), which starts the passes after it.
#include "shadetlm/tlm/stage.hpp"  // <systemc> first: the quantum keeper needs it
#include "shadetlm/modules/setup/setup_kernel.hpp"

#include <tlm_utils/tlm_quantumkeeper.h>

namespace shadetlm::modules {

class Setup : public sc_core::sc_module, public BlockInfo {
 public:
  tlm_utils::simple_initiator_socket<Setup> out;

  SC_HAS_PROCESS(Setup);
  Setup(sc_core::sc_module_name name, SetupKernel& kernel, Timing timing, sc_core::sc_time period);

  std::string block_name() const override { return basename(); }
  BlockStats stats() const override;
  const Timing& timing() const override { return timing_; }
  const BlockTimes& times() const override { return line_.times(); }
  void join_line(MainPassTiming* line, int) override;
  void keep_histogram(uint64_t cycles) override { line_.times().bin_cycles = cycles; }
  void bind_output(tlm::tlm_target_socket<32>& next) override { out.bind(next); }

 private:
  void run();
  bool traced(const TriangleSetup& t) const;  // in the timeline

  SetupKernel& kernel_;
  Timing timing_;
  TriangleLine line_;
  TimingLog* log_ = nullptr;
  sc_core::sc_time period_;
  tlm_utils::tlm_quantumkeeper quantum_;
  BlockStats stats_;
};

}  // namespace shadetlm::modules
