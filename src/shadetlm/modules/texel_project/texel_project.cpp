#include "shadetlm/modules/texel_project/texel_project.hpp"

namespace shadetlm::modules {

TexelProject::TexelProject(sc_core::sc_module_name name, TexelProjectKernel& kernel, Timing timing,
                           sc_core::sc_time)
    : sc_core::sc_module(name), in("in"), out("out"), kernel_(kernel), schedule_(timing) {
  in.bind(*this);
}

BlockStats TexelProject::stats() const {
  BlockStats s;
  s.packets = kernel_.polygons();
  s.pixels = kernel_.covered();
  s.ops = kernel_.ops();
  s.busy_cycles = schedule_.times().busy;
  return s;
}

void TexelProject::b_transport(tlm::tlm_generic_payload& trans, sc_core::sc_time& delay) {
  trans.set_response_status(tlm::TLM_OK_RESPONSE);
  if (!is_pass_end(trans)) return;  // (none come: the main pass's last block keeps them)
  PassEnd& e = *reinterpret_cast<PassEnd*>(trans.get_data_ptr());  // the end of the main pass: the frame
  if (e.framebuffer) {
    kernel_.run(*e.framebuffer);
    schedule_.occupy(e.cycle, kernel_.cycles());
    pass_ = {int64_t(e.cycle), int64_t(kernel_.cycles())};
  }
  e.cycle = std::max(e.cycle, uint64_t(schedule_.times().last + 1));
  if (out.size() > 0) out->b_transport(trans, delay);
}

}  // namespace shadetlm::modules
