#pragma once
// Classic bump mapping (bump-mapping paper, Fig. 2; Blinn 1978): the interpolators of
// n × Pv and Pu × n, and the perturbation of the interpolated normal by the fetched
// height-map derivatives,
//
//   N' = c·N + Fu (n × Pv) + Fv (Pu × n),     c = |Pu × Pv|,
//
// before the normalize block. Pu and Pv are unbounded (they scale with the surface's
// size over its uv range), so these datapaths carry wide values: the ranges the stats
// report. Only bump-classic packets come here; the others pass by.
#include <string>
#include <vector>

#include "shadetlm/numeric/number.hpp"
#include "shadetlm/tlm/kernel_parts.hpp"
#include "shadetlm/tlm/packet.hpp"
#include "shadetlm/numeric/range.hpp"

namespace shadetlm::modules {

class BumpPerturbKernel {
 public:
  static constexpr unsigned optional = Optional::ranges | Optional::numbers;  // (tlm/kernel_parts.hpp)
  // The interpolators, the products and the sums are of `format` (pipeline.bump_perturb.format).
  explicit BumpPerturbKernel(bool perspective, core::NumberFormat format = {})
      : perspective_(perspective), numbers_(format) {}
  static bool needed(const core::Scene& scene);

  void process(SpanPacket& p);
  NumberStats numbers() const { return {numbers_.format.name(), nonfinite_, numbers_.events}; }
  const Ops& ops() const { return ops_; }
  Work work(const SpanPacket&) const { return {nullptr, 1}; }  // a pixel a cycle
  bool bypass(const SpanPacket& p) const { return p.tri->material->path != core::ShadingPath::BumpClassic; }
  Ranges ranges() const { return {{"n_x_pv", n_x_pv_range_}, {"pu_x_n", pu_x_n_range_}, {"perturbed", perturbed_range_}}; }

  // Waveforms: n × Pv and Pu × n (x components), the perturbed normal.
  void set_capture(bool on) { capture_ = on; }
  static std::vector<std::string> trace_names() { return {"n_x_pv_x", "pu_x_n_x", "n_x", "n_y", "n_z"}; }
  void trace(const SpanPacket& p, int i, double* out) const {
    out[0] = captured_[0][i], out[1] = captured_[1][i];
    for (int c = 0; c < 3; ++c) out[2 + c] = p.n[c][i];
  }

  // Per pixel: the two vectors from their planes (6 mul by w, 6 add steps), the normal
  // from N/w (3 mul, perspective mode), c·N (3 mul), Fu·X and Fv·Y (6 mul), the sum (6 add).
  Ops ops_per_pixel() const { return {/*add*/ 12, /*mul*/ perspective_ ? 18u : 15u}; }
  static constexpr Ops kOpsPerSpan{/*add*/ 12, /*mul*/ 12};  // six plane seeds

 private:
  bool perspective_;
  NumberContext numbers_;
  Ops ops_;
  ValueRange n_x_pv_range_, pu_x_n_range_, perturbed_range_;
  bool capture_ = false;
  float captured_[2][kSpanMax] = {};
  template <class T> void perturb(SpanPacket& p);
  uint64_t nonfinite_ = 0;
};

}  // namespace shadetlm::modules
