#pragma once
// Normal interpolation by constant increments (normal-increments paper). Per triangle
// the walker starts from the seed at the reference pixel and moves pixel by pixel,
// adding one constant increment per step:
//
//   right along a span          N += ΔN_H
//   down, same column           N += ΔN_V
//   down and right (an edge)    N += ΔN_D = ΔN_H + ΔN_V
//   down and left  (an edge)    N += ΔN_A = ΔN_V − ΔN_H
//
// It follows the left edge from row to row (a row start that moves by more than one
// pixel adds further ±ΔN_H steps), then walks right along the row, through hidden
// pixels too, as a walker that only adds must. Affine mode walks N; perspective mode
// walks N/w, whose direction is that of the perspective-correct normal (1/w > 0), so
// the normalization that follows needs no per-pixel reciprocal.
#include <string>
#include <vector>

#include "shadetlm/numeric/number.hpp"
#include "shadetlm/tlm/kernel_parts.hpp"
#include "shadetlm/tlm/packet.hpp"
#include "shadetlm/numeric/range.hpp"

namespace shadetlm::modules {

class NormalInterpKernel {
 public:
  static constexpr unsigned optional = Optional::ranges | Optional::numbers;  // (tlm/kernel_parts.hpp)
  // reseed: 0 walks the whole triangle from its seed (the paper's); −1 takes every row
  // start from the plane; N > 0 also every N pixels along the row (normal_interp.reseed).
  // The walker's adders and registers are of `format` (pipeline.normal_interp.format):
  // the increments from setup are rounded to it as each packet starts.
  explicit NormalInterpKernel(int reseed = 0, core::NumberFormat format = {})
      : reseed_(reseed), numbers_(format), checks_(checks_outputs(format, false)) {}
  // A re-seed: a0 + ax·dx + ay·dy for three components.
  static constexpr Ops kOpsPerReseed{/*add*/ 6, /*mul*/ 6};
  void process(SpanPacket& p);
  const Ops& ops() const { return ops_; }
  uint64_t steps() const { return steps_; }  // increments added, all kinds
  // Work of the last packet: one step per pixel, hidden pixels and row changes included
  // (the first pixel's walk to it; per pixel where a tile re-seeds).
  Work work(const SpanPacket&) const { return tiled_ ? Work{work_, 0} : Work{nullptr, 1, nullptr, lead_}; }
  // Fetched-normal bump paths replace the interpolated normal (the paper's multiplexer
  // would discard it): their packets do not walk.
  bool bypass(const SpanPacket& p) const { return core::fetches_normal(p.tri->material->path); }
  Ranges ranges() const { return {{"n", range_}}; }
  NumberStats numbers() const { return {numbers_.format.name(), nonfinite_, numbers_.events, checks_}; }
  // Waveforms: the interpolated (not yet normalized) normal, N or N/w.
  void set_capture(bool) {}
  static std::vector<std::string> trace_names() { return {"n_x", "n_y", "n_z"}; }
  void trace(const SpanPacket& p, int i, double* out) const {
    for (int c = 0; c < 3; ++c) out[c] = p.n[c][i];
  }

 private:
  template <class T> void walk(SpanPacket& p);

  int reseed_ = 0;
  uint32_t triangle_ = ~0u;
  int row_y_ = 0, row_x_ = 0;   // the walker's row and row start
  double row_n_[3] = {0, 0, 0}; // the normal there (a value of the format, held exactly)
  int x_ = 0;                   // the walker's position along the row
  double n_[3] = {0, 0, 0};     // the normal there
  uint64_t steps_ = 0, last_steps_ = 0;
  uint32_t lead_ = 0;        // the first pixel's steps before its own
  bool tiled_ = false;       // the last packet re-seeded per tile: its work is per pixel
  uint16_t work_[kSpanMax];  // (then)
  Ops ops_;
  NumberContext numbers_;
  bool checks_;  // counts its non-finite outputs (checks_outputs: adders only)
  uint64_t nonfinite_ = 0;
  ValueRange range_;  // the walked normal, N or N/w
};

}  // namespace shadetlm::modules
