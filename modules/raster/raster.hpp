#pragma once
// The raster block: triangles in, span packets out (RasterKernel). Busy one II per
// pixel walked, hidden ones included; a packet leaves when the walk has reached it.
#include "shadetlm/modules/common/block.hpp"
#include "shadetlm/modules/raster/raster_kernel.hpp"

namespace shadetlm::modules {

class Raster : public sc_core::sc_module, public BlockInfo {
 public:
  tlm_utils::simple_target_socket<Raster> in;
  tlm_utils::simple_initiator_socket<Raster> out;

  Raster(sc_core::sc_module_name name, RasterKernel& kernel, Timing timing, sc_core::sc_time period);

  std::string block_name() const override { return basename(); }
  BlockStats stats() const override;
  const Schedule& schedule() const override { return schedule_; }
  Schedule& schedule() override { return schedule_; }
  tlm::tlm_target_socket<32>* input() override { return &in; }
  void bind_output(tlm::tlm_target_socket<32>& next) override { out.bind(next); }
  // Waveforms: 1/w and w of each visible pixel.
  static std::vector<std::string> trace_names() { return {"inv_w", "w"}; }

 private:
  void b_transport(tlm::tlm_generic_payload& trans, sc_core::sc_time& delay);

  RasterKernel& kernel_;
  Schedule schedule_;
  sc_core::sc_time period_;
  BlockStats stats_;
  tlm::tlm_generic_payload span_;
};

}  // namespace shadetlm::modules
