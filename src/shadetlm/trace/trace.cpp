#include "shadetlm/trace/trace.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "shadetlm/core/output.hpp"
#include "shadetlm/core/version.hpp"

namespace shadetlm::modules {

Tracer::Tracer(TraceRegion region, sc_core::sc_time period) : region_(region), period_(period) {}

int Tracer::add_probe(const std::string& block, const std::vector<std::string>& values) {
  sc_assert(values.size() <= size_t(kMaxValues));
  ProbeInfo info;
  info.block = block;
  for (const char* n : {"valid", "ready", "x", "y", "triangle"}) {
    info.names.push_back("shadetlm." + block + "." + n);
    info.is_real.push_back(false);
  }
  for (const auto& n : values) {  // "texel_x:int": an integer value
    const bool integer = n.size() > 4 && n.compare(n.size() - 4, 4, ":int") == 0;
    info.names.push_back("shadetlm." + block + "." + (integer ? n.substr(0, n.size() - 4) : n));
    info.is_real.push_back(!integer);
  }
  value_count_.push_back(values.size());
  info_.push_back(info);
  return int(info_.size() - 1);
}

void Tracer::record(int probe, uint64_t valid, uint64_t handed, int x, int y, uint32_t triangle,
                    const double* values) {
  Record& r = records_list_.emplace_back(Record{valid, handed, probe, x, y, triangle, {}});
  std::copy(values, values + value_count_[size_t(probe)], r.values.begin());
  first_ = records_ == 0 ? valid : std::min(first_, valid);
  last_ = std::max(last_, handed + 1);
  ++records_;
}

namespace {

// VCD identifiers: printable characters from '!' on, as digits.
std::string vcd_id(size_t n) {
  std::string id;
  do id += char('!' + n % 94), n /= 94;
  while (n > 0);
  return id;
}

// The VCD's text, gathered in a buffer written out in large pieces.
class VcdText {
 public:
  explicit VcdText(core::CheckedFile& file) : file_(file) {}
  ~VcdText() = default;
  VcdText& operator<<(std::string_view s) {
    text_ += s;
    if (text_.size() > (1u << 20)) flush();
    return *this;
  }
  void number(uint64_t n) {
    char b[24];
    text_.append(b, size_t(std::to_chars(b, b + sizeof b, n).ptr - b));
  }
  void binary(uint64_t v) {  // "b101"
    text_ += 'b';
    int top = 63;
    while (top > 0 && !(v >> top & 1)) --top;
    for (int k = top; k >= 0; --k) text_ += char('0' + (v >> k & 1));
  }
  void real(double v) {  // shortest text that reads back as v
    char b[32];
    text_ += 'r';
    text_.append(b, size_t(std::to_chars(b, b + sizeof b, v).ptr - b));
  }
  void flush() {
    file_.write(text_);
    text_.clear();
  }

 private:
  core::CheckedFile& file_;
  std::string text_;
};

}  // namespace

void Tracer::write_vcd(core::OutputSet& outputs, const std::string& path) {
  const double kUnknown = std::numeric_limits<double>::quiet_NaN();  // an integer written as x
  // The signals' current values: per probe valid, ready, x, y, triangle, then values.
  struct Signal {
    std::string id;
    bool real;
    double value;  // (integers held exactly)
    bool touched = false;  // set in this time step
    double written = 0;
  };
  std::vector<std::vector<Signal>> signals(info_.size());
  size_t next_id = 2;  // 0: end_of_trace, 1: cycle
  core::CheckedFile file(outputs.temporary(path), path);
  VcdText vcd(file);
  // One time unit a cycle, the model's own unit, so that a viewer's axis reads cycles.
  // VCD has no cycle unit: the unit is written as 1 ns (a 1 GHz clock), as the RTL's
  // waveform is, and the real clock is named in a comment.
  char period_ps[32];
  std::snprintf(period_ps, sizeof period_ps, "%.6g", period_.to_seconds() * 1e12);
  vcd << "$version shadetlm " << core::kVersion << " $end\n$timescale 1 ns $end\n"
      << "$comment one time unit is one cycle of the model's clock (" << std::string_view(period_ps) << " ps) $end\n"
      << "$scope module shadetlm $end\n"
      << "$var wire 1 " << vcd_id(0) << " end_of_trace $end\n"
      << "$var wire 64 " << vcd_id(1) << " cycle [63:0] $end\n";
  auto write_cycle = [&](uint64_t cycle) {
    vcd.binary(cycle);
    vcd << " " << vcd_id(1) << "\n";
  };
  for (size_t p = 0; p < info_.size(); ++p) {
    vcd << "$scope module " << info_[p].block << " $end\n";
    for (size_t k = 0; k < info_[p].names.size(); ++k) {
      Signal s{vcd_id(next_id++), info_[p].is_real[k], 0.0};
      const std::string name = info_[p].names[k].substr(info_[p].names[k].rfind('.') + 1);
      if (s.real) vcd << "$var real 64 " << s.id << " " << name << " $end\n";
      else if (k <= 1) vcd << "$var wire 1 " << s.id << " " << name << " $end\n";
      else vcd << "$var wire 32 " << s.id << " " << name << " [31:0] $end\n";
      if (k > 1 && !s.real) s.value = kUnknown;  // x until a pixel is valid
      signals[p].push_back(s);
    }
    vcd << "$upscope $end\n";
  }
  vcd << "$upscope $end\n$enddefinitions $end\n";
  // A time step's changes: each signal set in it whose value differs from what was last
  // written (all of them at the start).
  std::vector<std::pair<int, size_t>> touched;
  auto set = [&](int p, size_t k, double value) {
    Signal& s = signals[size_t(p)][k];
    if (!s.touched) touched.emplace_back(p, k), s.touched = true;
    s.value = value;
  };
  auto write = [&](size_t k, Signal& s) {
    if (s.real) vcd.real(s.value);
    else if (k <= 1) vcd << (s.value != 0 ? "1" : "0");
    else if (std::isnan(s.value)) vcd << "bx";
    else vcd.binary(uint32_t(int64_t(s.value)));
    vcd << (s.real || k > 1 ? " " : "") << s.id << "\n";
    s.written = s.value;
  };
  auto dump = [&](bool all) {
    if (all)
      for (auto& probe : signals)
        for (size_t k = 0; k < probe.size(); ++k) write(k, probe[k]);
    for (const auto& [p, k] : touched) {
      Signal& s = signals[size_t(p)][k];
      s.touched = false;
      if (!all && std::memcmp(&s.value, &s.written, sizeof s.value) != 0) write(k, s);
    }
    touched.clear();
  };
  vcd << "#0\n$dumpvars\n0" << vcd_id(0) << "\n";
  write_cycle(0);
  dump(true);
  vcd << "$end\n";
  std::vector<Event> events;  // three a record: its pixel, its handshake, then gone
  events.reserve(records_list_.size() * 3);
  for (uint32_t k = 0; k < records_list_.size(); ++k) {
    const Record& r = records_list_[k];
    events.push_back({r.valid, 1, k}), events.push_back({r.handed, 2, k}), events.push_back({r.handed + 1, 0, k});
  }
  std::sort(events.begin(), events.end());
  for (size_t e = 0; e < events.size();) {
    const uint64_t cycle = events[e].cycle;
    for (; e < events.size() && events[e].cycle == cycle; ++e) {
      const Record& r = records_list_[events[e].record];
      std::vector<Signal>& s = signals[size_t(r.probe)];
      if (events[e].kind == 0) {  // not valid: the integers x, the reals hold (valid qualifies them)
        set(r.probe, 0, 0), set(r.probe, 1, 0);
        for (size_t k = 2; k < s.size(); ++k)
          if (!s[k].real) set(r.probe, k, kUnknown);
      } else if (events[e].kind == 2) {
        set(r.probe, 1, 1);
      } else {
        set(r.probe, 0, 1), set(r.probe, 2, r.x), set(r.probe, 3, r.y), set(r.probe, 4, r.triangle);
        for (size_t k = 0; k < value_count_[size_t(r.probe)]; ++k) set(r.probe, 5 + k, r.values[k]);
      }
    }
    if (cycle == 0) {
      dump(false);  // (at #0, after the initial values)
      continue;
    }
    vcd << "#";
    vcd.number(cycle);
    vcd << "\n";
    write_cycle(cycle);
    dump(false);
  }
  // The dump runs 10 % past the traced span, so that a viewer's window on the whole
  // span fits inside it (GTKWave ignores a start time otherwise), where end_of_trace rises.
  const uint64_t end = std::max<uint64_t>(last_ + (last_ - first_) / 10 + 1, 1);
  vcd << "#";
  vcd.number(end);
  vcd << "\n1" << vcd_id(0) << "\n";
  write_cycle(end);
  vcd << "#";
  vcd.number(end + 1);
  vcd << "\n";
  vcd.flush();
  file.close();
}

}  // namespace shadetlm::modules
