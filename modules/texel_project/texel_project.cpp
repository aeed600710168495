#include "modules/texel_project/texel_project.hpp"

namespace modules {

TexelProject::TexelProject(sc_core::sc_module_name name, TexelProjectKernel& kernel, FramebufferKernel& framebuffer,
                           const Setup& setup, const BlockInfo& last_block, Timing timing, sc_core::sc_time period)
    : sc_core::sc_module(name),
      kernel_(kernel),
      framebuffer_(framebuffer),
      setup_(setup),
      last_block_(last_block),
      schedule_(timing),
      period_(period) {
  SC_THREAD(run);
}

BlockStats TexelProject::stats() const {
  BlockStats s;
  s.packets = kernel_.polygons();
  s.pixels = kernel_.covered();
  s.ops = kernel_.ops();
  s.busy_cycles = schedule_.busy_cycles();
  return s;
}

void TexelProject::run() {
  if (!setup_.finished()) wait(setup_.done);
  kernel_.run(framebuffer_);
  // The pass starts when the last pixel of the frame is written.
  const uint64_t start = last_block_.schedule().free_cycle() + last_block_.schedule().timing().latency;
  schedule_.occupy(start, kernel_.cycles());
}

}  // namespace modules
