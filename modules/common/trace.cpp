#include "shadetlm/modules/common/trace.hpp"

#include <algorithm>

namespace shadetlm::modules {

Tracer::Tracer(sc_core::sc_module_name name, const std::string& vcd_path, TraceRegion region,
               sc_core::sc_time period)
    : sc_core::sc_module(name), region_(region), period_(period) {
  // sc_create_vcd_trace_file appends ".vcd" itself.
  std::string base = vcd_path;
  if (base.size() > 4 && base.compare(base.size() - 4, 4, ".vcd") == 0) base.resize(base.size() - 4);
  file_ = sc_core::sc_create_vcd_trace_file(base.c_str());
  file_->set_time_unit(1.0, sc_core::SC_PS);
  sc_core::sc_trace(file_, end_, "shadetlm.end_of_trace");
  SC_THREAD(run);
}

Tracer::~Tracer() {
  if (file_) sc_core::sc_close_vcd_trace_file(file_);
}

int Tracer::add_probe(const std::string& block, const std::vector<std::string>& values) {
  sc_assert(values.size() <= size_t(kMaxValues));
  auto probe = std::make_unique<Probe>();
  probe->values.assign(values.size(), 0.0);
  ProbeInfo info;
  info.block = block;
  // The VCD writer puts every signal under its own top scope, "SystemC".
  const std::string prefix = "shadetlm." + block + ".";
  auto add = [&](auto& var, const std::string& n, bool real) {
    sc_core::sc_trace(file_, var, prefix + n);
    info.names.push_back("SystemC." + prefix + n);
    info.is_real.push_back(real);
  };
  add(probe->valid, "valid", false);
  add(probe->ready, "ready", false);
  add(probe->x, "x", false);
  add(probe->y, "y", false);
  add(probe->triangle, "triangle", false);
  for (size_t k = 0; k < values.size(); ++k) add(probe->values[k], values[k], true);
  probes_.push_back(std::move(probe));
  info_.push_back(info);
  return int(probes_.size() - 1);
}

void Tracer::record(int probe, uint64_t valid, uint64_t handed, int x, int y, uint32_t triangle,
                    const double* values) {
  Event e{valid, 1, seq_++, probe, x, y, triangle, {}};
  std::copy(values, values + probes_[probe]->values.size(), e.values.begin());
  queue_.push(e);
  queue_.push({handed, 2, seq_++, probe, 0, 0, 0, {}});      // the handshake
  queue_.push({handed + 1, 0, seq_++, probe, 0, 0, 0, {}});  // then gone
  const uint64_t cycle = valid;
  first_ = records_ == 0 ? cycle : std::min(first_, cycle);
  last_ = std::max(last_, handed + 1);
  ++records_;
  // Wake the replay only if this record comes before what it waits for.
  if (cycle < next_wake_) wake_.notify(sc_core::SC_ZERO_TIME);
}

void Tracer::source_done() {
  source_done_ = true;
  wake_.notify(sc_core::SC_ZERO_TIME);
}

void Tracer::run() {
  while (true) {
    if (queue_.empty()) {
      next_wake_ = UINT64_MAX;  // idle: any record wakes the replay
      if (source_done_) {
        // Extend the dump 10 % past the traced span, so that a viewer's window on the
        // whole span fits inside it (GTKWave ignores a start time otherwise).
        const sc_core::sc_time end = period_ * double(last_ + (last_ - first_) / 10 + 1);
        if (end > sc_core::sc_time_stamp()) sc_core::wait(end - sc_core::sc_time_stamp());
        end_ = true;
        // The VCD writer writes a time step's values only when time moves on from it.
        sc_core::wait(period_);
        return;
      }
      sc_core::wait(wake_);
      continue;
    }
    const sc_core::sc_time at = period_ * double(queue_.top().cycle);
    const sc_core::sc_time now = sc_core::sc_time_stamp();
    if (at > now) {
      next_wake_ = queue_.top().cycle;
      sc_core::wait(at - now, wake_);  // a new, earlier record may arrive meanwhile
      next_wake_ = UINT64_MAX;
      continue;
    }
    while (!queue_.empty() && period_ * double(queue_.top().cycle) <= now) {
      const Event& e = queue_.top();
      Probe& p = *probes_[e.probe];
      if (e.kind == 0) {
        p.valid = p.ready = false;
      } else if (e.kind == 2) {
        p.ready = true;
      } else {
        p.valid = true;
        p.x = e.x;
        p.y = e.y;
        p.triangle = e.triangle;
        std::copy(e.values.begin(), e.values.begin() + p.values.size(), p.values.begin());
      }
      queue_.pop();
    }
  }
}

}  // namespace shadetlm::modules
