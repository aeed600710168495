#pragma once
// The texel_project block as a SystemC module: a thread that waits for the frame's
// rasterization to finish (setup's `done`), then runs the second pass of
// TexelProjectKernel on the framebuffer; its cycles start when the framebuffer has
// written its last pixel.
#include "modules/common/block.hpp"
#include "modules/setup/setup.hpp"
#include "modules/texel_project/texel_project_kernel.hpp"

namespace modules {

class TexelProject : public sc_core::sc_module, public BlockInfo {
 public:
  SC_HAS_PROCESS(TexelProject);
  TexelProject(sc_core::sc_module_name name, TexelProjectKernel& kernel, FramebufferKernel& framebuffer,
               const Setup& setup, const BlockInfo& last_block, Timing timing, sc_core::sc_time period);

  std::string block_name() const override { return basename(); }
  BlockStats stats() const override;
  const Schedule& schedule() const override { return schedule_; }
  Schedule& schedule() override { return schedule_; }

 private:
  void run();

  TexelProjectKernel& kernel_;
  FramebufferKernel& framebuffer_;
  const Setup& setup_;
  const BlockInfo& last_block_;
  Schedule schedule_;
  sc_core::sc_time period_;
};

}  // namespace modules
