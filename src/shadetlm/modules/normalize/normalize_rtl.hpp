#pragma once
// pipeline.normalize.impl = rtl (docs/rtl.md): the normalize block's packets through the
// RTL unit (rtl/normalize/normalize_unit.sv) verilated into a SystemC module, in place
// of the C++ kernel.
//
// The transactor turns a span packet into pin activity: the packet's pixels offered one a
// cycle on in_valid/in_ready (ΔN_H and c with the first), the unit normals taken from
// out_valid/out_ready, the words in the block's fixed-point format. It steps the RTL's
// clock in delta cycles: simulated time does not move, the pipeline's cycles are kept
// by its calendar as for every block. At the pins it checks, pixel by pixel, that the
// RTL keeps the timing the model declares for the block: each pixel taken II · work
// cycles after the one before, and put out II · (work − 1) + latency cycles after it was
// taken; a difference stops the run with both figures.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "shadetlm/numeric/number.hpp"
#include "shadetlm/tlm/kernel_parts.hpp"
#include "shadetlm/tlm/packet.hpp"
#include "shadetlm/stats/report.hpp"
#include "shadetlm/modules/normalize/normalize_kernel.hpp"

namespace shadetlm::modules {

// Whether this build has the RTL (Verilator found, SHADETLM_RTL on), and
// what it was built for ("fixed:3.20; exact latency 40 II 3, …"; or why it has none).
bool normalize_rtl_built();
std::string normalize_rtl_build();

class NormalizeRtlPins;  // the verilated unit and the signals on its pins

class NormalizeRtlKernel {
 public:
  static constexpr unsigned optional = Optional::numbers | Optional::details;  // (tlm/kernel_parts.hpp)
  // Throws core::InputError naming `scene_file` and the setting when this build has no
  // RTL, or its RTL was built for another format or timing than `format` and `timing`.
  NormalizeRtlKernel(NormalizeMode mode, core::NumberFormat format, Timing timing, const std::string& scene_file);
  ~NormalizeRtlKernel();

  void process(SpanPacket& p);
  Ops ops() const;
  Work work(const SpanPacket&) const;
  bool bypass(const SpanPacket&) const { return false; }
  // The RTL counts no saturations: its outputs are not tested here.
  NumberStats numbers() const { return {format_.name(), 0, {}, false}; }
  nlohmann::json details() const;
  void set_capture(bool) {}
  static std::vector<std::string> trace_names() { return {"n_x", "n_y", "n_z"}; }
  void trace(const SpanPacket& p, int i, double* out) const {
    for (int c = 0; c < 3; ++c) out[c] = p.n[c][i];
  }

 private:
  void check_timing(const SpanPacket& p, const int64_t* taken, const int64_t* out) const;
  // A word on the pins: the format's 1 + I + F bits of a raw value, two's complement.
  uint64_t word_mask() const { return ~uint64_t(0) >> (64 - (1 + format_.int_bits + format_.frac_bits)); }
  int64_t sign_extend(uint64_t word) const {
    const int shift = 64 - (1 + format_.int_bits + format_.frac_bits);
    return int64_t(word << shift) >> shift;
  }

  NormalizeMode mode_;
  core::NumberFormat format_;
  Timing timing_;
  std::string scene_file_;
  std::unique_ptr<NormalizeRtlPins> pins_;
  NumberContext numbers_;  // the format, for the conversions at the pins
  PacketTally<2> tally_;  // as the kernel's: mode_ (0), forward-difference bump packets (1)
  uint64_t cycles_ = 0;   // clocked, over the run
  bool reset_ = false;    // the RTL has been reset
};

}  // namespace shadetlm::modules
