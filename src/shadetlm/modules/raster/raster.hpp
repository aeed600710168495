#pragma once
// The raster block: triangles in, span packets out (RasterKernel). It walks one pixel a
// II, hidden ones included, and holds the main pass's timing: each packet, once back
// from the chain, is timed in the MainPassTiming (timing/main_pass.hpp), and the
// triangle's transaction returns the cycle the raster took it (setup's back-pressure).
#include "shadetlm/tlm/stage.hpp"
#include "shadetlm/modules/raster/raster_kernel.hpp"

namespace shadetlm::modules {

class Raster : public sc_core::sc_module, public BlockInfo {
 public:
  tlm_utils::simple_target_socket<Raster> in;
  tlm_utils::simple_initiator_socket<Raster> out;

  Raster(sc_core::sc_module_name name, RasterKernel& kernel, Timing timing, sc_core::sc_time period);

  std::string block_name() const override { return basename(); }
  BlockStats stats() const override;
  const Timing& timing() const override { return timing_; }
  const BlockTimes& times() const override { return line_ ? line_->times(0) : no_times_; }
  void join_line(MainPassTiming* line, int) override { line_ = line; }
  void keep_histogram(uint64_t cycles) override {
    if (line_) line_->times(0).bin_cycles = cycles;
  }
  tlm::tlm_target_socket<32>* input() override { return &in; }
  void bind_output(tlm::tlm_target_socket<32>& next) override { out.bind(next); }
  void timed(const SpanPacket& p) override;
  // Waveforms: 1/w and w of each visible pixel.
  static std::vector<std::string> trace_names() { return {"inv_w", "w"}; }

 private:
  void b_transport(tlm::tlm_generic_payload& trans, sc_core::sc_time& delay);

  RasterKernel& kernel_;
  Timing timing_;
  sc_core::sc_time period_;
  MainPassTiming* line_ = nullptr;
  BlockTimes no_times_;
  BlockStats stats_;
  tlm::tlm_generic_payload span_;
  std::vector<StepLines> misses_;  // a hidden run's depth misses, for the MainPassTiming
};

}  // namespace shadetlm::modules
