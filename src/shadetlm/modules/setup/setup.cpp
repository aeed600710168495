#include "shadetlm/modules/setup/setup.hpp"

namespace shadetlm::modules {

Setup::Setup(sc_core::sc_module_name name, SetupKernel& kernel, Timing timing, sc_core::sc_time period)
    : sc_core::sc_module(name), out("out"), kernel_(kernel), timing_(timing),
      line_(timing, Timing{}.fifo_depth), period_(period) {
  SC_THREAD(run);
}

void Setup::join_line(MainPassTiming* line, int) {
  const uint64_t bins = line_.times().bin_cycles;
  line_ = TriangleLine(timing_, line->timing(0).fifo_depth);  // the raster's triangle FIFO
  line_.times().bin_cycles = bins;
  log_ = line->log();
}

BlockStats Setup::stats() const {
  BlockStats s = stats_;
  s.ops = kernel_.ops();
  s.busy_cycles = line_.times().busy;
  s.blocked_cycles = line_.times().blocked;
  return s;
}

// With a traced region, the triangles whose covered pixels may reach into it.
bool Setup::traced(const TriangleSetup& t) const {
  if (!triangle_kept(t.id)) return false;
  const core::SnappedTriangle& c = t.coverage;
  return !filter_ || (c.x1 >= filter_->x0 && c.x0 <= filter_->x1 && c.y1 >= filter_->y0 && c.y0 <= filter_->y1);
}

void Setup::run() {
  quantum_.reset();
  tlm::tlm_generic_payload trans;
  trans.set_command(tlm::TLM_WRITE_COMMAND);
  kernel_.run([&](const TriangleSetup& t) {
    line_.reject(kernel_.take_rejected(), kernel_.reject_cycles);  // the triangles dropped before it
    const int64_t handed = line_.next();
    ++stats_.packets;
    if (kTracing && timeline_ && traced(t)) timeline_->add_triangle(track_, uint64_t(line_.last_start()), timing_.ii, t.id);
    if (log_) log_->triangle(t.id, line_.last_start(), handed);
    trans.set_data_ptr(reinterpret_cast<unsigned char*>(const_cast<TriangleSetup*>(&t)));
    trans.set_data_length(sizeof(TriangleSetup));
    trans.set_address(t.id);
    // The triangle reaches the raster at `handed`; the raster returns the cycle it took
    // it. Never negative: the quantum keeper syncs to a cycle before `handed`.
    const sc_core::sc_time now = sc_core::sc_time_stamp();
    const sc_core::sc_time at = period_ * double(handed);
    sc_assert(at >= now);
    sc_core::sc_time delay = at - now;
    out->b_transport(trans, delay);
    line_.taken(int64_t((now + delay) / period_ + 0.5));
    quantum_.set(period_ * double(line_.last_start() + int64_t(timing_.ii)) - now);
    if (quantum_.need_sync()) quantum_.sync();
  });
  line_.reject(kernel_.take_rejected(), kernel_.reject_cycles);
  quantum_.sync();
  // Every transaction is a blocking call: the blocks downstream are done with the frame.
  PassEnd end;
  end.cycle = uint64_t(line_.times().last + 1);
  trans.set_command(tlm::TLM_IGNORE_COMMAND);
  trans.set_data_ptr(reinterpret_cast<unsigned char*>(&end));
  trans.set_data_length(sizeof(PassEnd));
  sc_core::sc_time delay = sc_core::SC_ZERO_TIME;
  out->b_transport(trans, delay);
}

}  // namespace shadetlm::modules
