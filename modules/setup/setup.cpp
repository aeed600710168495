#include "shadetlm/modules/setup/setup.hpp"

namespace shadetlm::modules {

Setup::Setup(sc_core::sc_module_name name, SetupKernel& kernel, Timing timing, sc_core::sc_time period)
    : sc_core::sc_module(name), out("out"), kernel_(kernel), schedule_(timing), period_(period) {
  SC_THREAD(run);
}

BlockStats Setup::stats() const {
  BlockStats s = stats_;
  s.ops = kernel_.ops();
  s.busy_cycles = schedule_.busy_cycles();
  return s;
}

void Setup::run() {
  quantum_.reset();
  tlm::tlm_generic_payload trans;
  trans.set_command(tlm::TLM_WRITE_COMMAND);
  uint64_t local_cycle = 0;
  kernel_.run([&](const TriangleSetup& t) {
    const uint64_t arrival = schedule_.occupy(local_cycle, 1);  // one triangle
    ++stats_.packets;
    if (kTracing && timeline_ && triangle_kept(t.id))
      timeline_->add(track_, schedule_.last_start(), schedule_.last_busy(), 0, t.id);
    trans.set_data_ptr(reinterpret_cast<unsigned char*>(const_cast<TriangleSetup*>(&t)));
    trans.set_data_length(sizeof(TriangleSetup));
    trans.set_address(t.id);
    // The triangle reaches the raster at `arrival`: the raster reads it from there.
    // Never negative: the quantum keeper syncs to period·local_cycle ≤ period·arrival.
    const sc_core::sc_time at = period_ * double(arrival);
    sc_assert(at >= sc_core::sc_time_stamp());
    sc_core::sc_time delay = at - sc_core::sc_time_stamp();
    out->b_transport(trans, delay);
    local_cycle = schedule_.free_cycle();
    quantum_.set(period_ * double(local_cycle) - sc_core::sc_time_stamp());
    if (quantum_.need_sync()) quantum_.sync();
  });
  quantum_.sync();
  // Every transaction is a blocking call: the blocks downstream are done with the frame.
  PassEnd end;
  pass_end(end);
  trans.set_command(tlm::TLM_IGNORE_COMMAND);
  trans.set_data_ptr(reinterpret_cast<unsigned char*>(&end));
  trans.set_data_length(sizeof(PassEnd));
  sc_core::sc_time delay = sc_core::SC_ZERO_TIME;
  out->b_transport(trans, delay);
  if (tracer_) tracer_->source_done();
}

}  // namespace shadetlm::modules
