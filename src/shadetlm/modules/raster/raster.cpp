#include "shadetlm/modules/raster/raster.hpp"

namespace shadetlm::modules {

Raster::Raster(sc_core::sc_module_name name, RasterKernel& kernel, Timing timing, sc_core::sc_time period)
    : sc_core::sc_module(name), in("in"), out("out"), kernel_(kernel), timing_(timing), period_(period) {
  in.register_b_transport(this, &Raster::b_transport);
  span_.set_command(tlm::TLM_WRITE_COMMAND);
}

BlockStats Raster::stats() const {
  BlockStats s = stats_;
  s.ops = kernel_.ops();
  const BlockTimes& t = times();
  s.busy_cycles = t.busy, s.starved_cycles = t.starved, s.blocked_cycles = t.blocked;
  s.memory_stall_cycles = t.memory_stall;
  return s;
}

void Raster::b_transport(tlm::tlm_generic_payload& trans, sc_core::sc_time& delay) {
  if (is_pass_end(trans)) {
    PassEnd& e = *reinterpret_cast<PassEnd*>(trans.get_data_ptr());
    if (line_) line_->settle(), e.cycle = std::max(e.cycle, uint64_t(line_->end()));
    return out->b_transport(trans, delay);
  }
  const TriangleSetup& t = *reinterpret_cast<const TriangleSetup*>(trans.get_data_ptr());
  const sc_core::sc_time now = sc_core::sc_time_stamp();  // the same for every packet of the triangle
  const int64_t arrival = int64_t((now + delay) / period_ + 0.5);
  const int64_t taken = line_ ? line_->start_triangle(arrival) : arrival;
  TimingLog* log = line_ ? line_->log() : nullptr;
  if (log) log->taken(taken);
  // The packets leave with the cycle the raster took the triangle; their pixels' times
  // follow from the sweep once the chain is done with them.
  const sc_core::sc_time sent = period_ * double(taken) - now;
  const uint64_t walked_before = kernel_.pixels_walked();
  uint64_t timed_steps = 0;  // of the triangle's walk, up to the last pixel timed
  size_t misses_taken = 0;   // of kernel_.hidden_lines()
  // The hidden pixels that missed among the walk's steps [from, to) of the triangle,
  // by their step from `from`.
  auto hidden_misses = [&](uint64_t from, uint64_t to) -> const std::vector<StepLines>& {
    misses_.clear();
    const auto& all = kernel_.hidden_lines();
    for (; misses_taken < all.size() && all[misses_taken].step - walked_before < to; ++misses_taken)
      misses_.push_back({all[misses_taken].step - walked_before - from, all[misses_taken].lines});
    return misses_;
  };
  kernel_.run(t, [&](SpanPacket& p) {
    ++stats_.packets;
    stats_.pixels += uint64_t(p.count);
    span_.set_data_ptr(reinterpret_cast<unsigned char*>(&p));
    span_.set_data_length(sizeof(SpanPacket));
    span_.set_address(uint64_t(p.y) << 32 | uint32_t(p.x0));
    sc_core::sc_time d = sent;
    out->b_transport(span_, d);
    // The walk's steps before the packet's first pixel, hidden ones included.
    const uint64_t first = kernel_.row_walked_before() - walked_before + uint64_t(p.x0 - p.row_start);
    if (line_ && line_->dram()) {  // the depth buffer's traffic: the packet's and the hidden pixels' before it
      line_->set_work(0, kernel_.work());
      line_->sweep(p, first - timed_steps, hidden_misses(timed_steps, first));
    } else if (line_) {
      line_->sweep(p, first - timed_steps);
    }
    timed_steps = first + uint64_t(p.count);
  });
  const uint64_t trailing = kernel_.pixels_walked() - walked_before - timed_steps;
  if (line_ && line_->dram()) line_->walk_hidden(trailing, hidden_misses(timed_steps, timed_steps + trailing));
  else if (line_) line_->walk_hidden(trailing);
  kernel_.hidden_lines().clear();
  if (log) log->trailing(trailing);
  // Setup's back-pressure: the transaction returns the cycle the raster took it.
  delay = sent;
  trans.set_response_status(tlm::TLM_OK_RESPONSE);
}

void Raster::timed(const SpanPacket& p) {
  if (!kTracing || p.count == 0) return;
  record_timed(p, *line_, 0, [&](int i, double* v) { v[0] = p.inv_w[i], v[1] = p.w[i]; });
}

}  // namespace shadetlm::modules
