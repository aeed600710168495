#pragma once
// The texel_project block as a SystemC module: a pass of its own after the main chain.
// The end of that pass (PassEnd, from the framebuffer) brings the frame; the module runs
// the second pass of TexelProjectKernel on it, its cycles starting when the main pass
// has put out its last pixel, and hands the end of its own pass on.
#include "shadetlm/tlm/stage.hpp"
#include "shadetlm/modules/texel_project/texel_project_kernel.hpp"

namespace shadetlm::modules {

class TexelProject : public sc_core::sc_module, public BlockInfo, public PacketTarget {
 public:
  tlm::tlm_target_socket<32> in;
  tlm_utils::simple_initiator_socket_optional<TexelProject> out;

  TexelProject(sc_core::sc_module_name name, TexelProjectKernel& kernel, Timing timing, sc_core::sc_time period);

  std::string block_name() const override { return basename(); }
  BlockStats stats() const override;
  const Timing& timing() const override { return schedule_.timing(); }
  const BlockTimes& times() const override { return schedule_.times(); }
  void keep_histogram(uint64_t cycles) override { schedule_.times().bin_cycles = cycles; }
  PassWork pass_work() const override { return pass_; }
  tlm::tlm_target_socket<32>* input() override { return &in; }
  void bind_output(tlm::tlm_target_socket<32>& next) override { out.bind(next); }

 private:
  void b_transport(tlm::tlm_generic_payload& trans, sc_core::sc_time& delay) override;

  TexelProjectKernel& kernel_;
  Schedule schedule_;
  PassWork pass_;
};

}  // namespace shadetlm::modules
