#pragma once
// Normalization of the interpolated normal, in five variants (normal-increments paper,
// formulas (13)–(16), and the fast inverse square roots a designer would weigh):
//
//   exact               r = x² + y² + z²; N · (1 / sqrt(r))
//   forward-difference  r by second-order differences along the packet:
//                         R_0 = |N_0|², δ_0 = 2 N_0·ΔN_H + |ΔN_H|², R_{n+1} = R_n + δ_n,
//                         δ_{n+1} = δ_n + c, c = 2|ΔN_H|² (from setup);
//                       two additions per pixel and no multiplication, then N · rsqrt(r);
//                       a bump-mapped packet, whose normals do not step by ΔN_H, takes
//                       r direct into the same rsqrt unit
//   rsqrt0|1|2          r direct; the bit-level inverse square root estimate
//                       (one table-like look-up) refined by 0, 1 or 2 Newton steps
//                       y ← y (3/2 − r/2 · y²)
//
// The kernels are templates over the number type, so that a testbench can run them on
// Counted<float> and check the operation counts declared here.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "shadetlm/modules/common/number.hpp"
#include "shadetlm/modules/common/packet.hpp"
#include "shadetlm/modules/common/vectors.hpp"

namespace shadetlm::modules {

enum class NormalizeMode { Exact, ForwardDifference, Rsqrt0, Rsqrt1, Rsqrt2 };
// The modes' names (pipeline.normalize.mode), in the order of NormalizeMode.
const std::vector<std::string>& normalize_mode_names();
NormalizeMode parse_normalize_mode(const std::string& name);

// The fast inverse square root: an estimate from the float's bits (the exponent
// halved and negated, a magic constant correcting the mantissa), then Newton steps.
template <class T>
float rsqrt_estimate(T r) {
  float rf = float(value(r)), yf;
  uint32_t bits;
  std::memcpy(&bits, &rf, sizeof bits);
  bits = 0x5f3759dfu - (bits >> 1);  // one integer subtraction (the shift is wiring)
  std::memcpy(&yf, &bits, sizeof yf);
  return yf;
}
template <class T>
T fast_rsqrt(T r, int newton_steps) {
  T y = rsqrt_estimate(r);
  if (newton_steps == 0) return y;
  const T half_r = T(0.5f) * r;
  for (int i = 0; i < newton_steps; ++i) y = y * (T(1.5f) - half_r * y * y);
  return y;
}
template <class T>
Counted<T> fast_rsqrt(Counted<T> r, int newton_steps) {
  tally_counted<T>(Ops{/*add*/ 1});
  Counted<T> y = rsqrt_estimate(r.v);
  if (newton_steps == 0) return y;
  const Counted<T> half_r = Counted<T>(T(0.5f)) * r;
  for (int i = 0; i < newton_steps; ++i) y = y * (Counted<T>(T(1.5f)) - half_r * y * y);
  return y;
}

// One pixel: scales n to unit length given its radicand r = |n|².
template <class T>
void scale_by_rsqrt(T n[3], T r, NormalizeMode mode) {
  T s;
  switch (mode) {
    case NormalizeMode::Exact: s = T(1.0f) / sqrt_op(r); break;
    case NormalizeMode::ForwardDifference: s = rsqrt_op(r); break;
    case NormalizeMode::Rsqrt0: s = fast_rsqrt(r, 0); break;
    case NormalizeMode::Rsqrt1: s = fast_rsqrt(r, 1); break;
    default: s = fast_rsqrt(r, 2); break;
  }
  n[0] = n[0] * s;
  n[1] = n[1] * s;
  n[2] = n[2] * s;
}

template <class T>
T radicand(const T n[3]) {
  return n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
}

// |N_n|² along a span N_n = N_0 + n·ΔN_H by second-order differences (formulas
// (13)–(16)): seeded once per span, then two additions per pixel.
template <class T>
class RadicandSequence {
 public:
  RadicandSequence(const T n0[3], const T dh[3], T c)
      : r_(radicand(n0)), delta_(T(2.0f) * (n0[0] * dh[0] + n0[1] * dh[1] + n0[2] * dh[2]) + T(0.5f) * c), c_(c) {}
  T next() {  // R_n, then advances to R_{n+1}
    const T r = r_;
    r_ = r_ + delta_;
    delta_ = delta_ + c_;
    return r;
  }

 private:
  T r_, delta_, c_;
};

// Normalizes each pixel with its radicand computed directly; one straight loop per
// mode (a template parameter), which the compiler can vectorize.
template <NormalizeMode M, class T>
void normalize_pixels(T* nx, T* ny, T* nz, int count) {
  for (int i = 0; i < count; ++i) {
    T n[3] = {nx[i], ny[i], nz[i]};
    scale_by_rsqrt(n, radicand(n), M);
    nx[i] = n[0], ny[i] = n[1], nz[i] = n[2];
  }
}

// Normalizes the `count` (≤ kSpanMax) normals of a span whose normals step by dh (ΔN_H)
// from one pixel to the next; c = 2|ΔN_H|².
// With `direct`, forward-difference mode takes each radicand directly (bump packets).
template <class T>
void normalize_span(T* nx, T* ny, T* nz, int count, const T dh[3], T c, NormalizeMode mode, bool direct = false) {
  if (mode == NormalizeMode::ForwardDifference && direct)
    return normalize_pixels<NormalizeMode::ForwardDifference>(nx, ny, nz, count);
  if (mode == NormalizeMode::ForwardDifference) {
    if (count == 0) return;
    const T n0[3] = {nx[0], ny[0], nz[0]};
    // The radicands first (a chain of additions), then the scaling in a straight loop
    // of its own, which vectorizes.
    RadicandSequence<T> radicands(n0, dh, c);
    T r[kSpanMax];
    for (int i = 0; i < count; ++i) r[i] = radicands.next();
    for (int i = 0; i < count; ++i) {
      T n[3] = {nx[i], ny[i], nz[i]};
      scale_by_rsqrt(n, r[i], mode);
      nx[i] = n[0], ny[i] = n[1], nz[i] = n[2];
    }
    return;
  }
  switch (mode) {
    case NormalizeMode::Exact: normalize_pixels<NormalizeMode::Exact>(nx, ny, nz, count); break;
    case NormalizeMode::Rsqrt0: normalize_pixels<NormalizeMode::Rsqrt0>(nx, ny, nz, count); break;
    case NormalizeMode::Rsqrt1: normalize_pixels<NormalizeMode::Rsqrt1>(nx, ny, nz, count); break;
    default: normalize_pixels<NormalizeMode::Rsqrt2>(nx, ny, nz, count); break;
  }
}

// Operations per pixel and per packet (span), as the code above performs them.
Ops normalize_ops_per_pixel(NormalizeMode mode);
Ops normalize_ops_per_span(NormalizeMode mode);
// Forward-difference mode's bump packets: the radicand direct, then the rsqrt unit.
Ops normalize_ops_per_pixel_direct_rsqrt();

class NormalizeKernel {
 public:
  // The radicand and inverse square root datapaths are of `format`
  // (pipeline.normalize.format).
  explicit NormalizeKernel(NormalizeMode mode, core::NumberFormat format = {}) : mode_(mode), numbers_(format) {
    for (auto& w : seeded_) w = 1;
    seeded_[0] = 2;
  }
  void process(SpanPacket& p);
  Ops ops() const;
  NormalizeMode mode() const { return mode_; }
  // A pixel a cycle; the forward-difference radicand's seed (R0, δ0: 8 multiplications,
  // 5 additions) takes the multipliers a cycle before each packet's first pixel.
  Work work(const SpanPacket&) const {
    return mode_ == NormalizeMode::ForwardDifference ? Work{seeded_, 0} : Work{nullptr, 1};
  }
  bool bypass(const SpanPacket&) const { return false; }
  NumberStats numbers() const { return {numbers_.format.name(), nonfinite_, numbers_.events}; }
  // Waveforms: the radicand |N|² of the incoming normal (kept only for traced
  // packets) and the normalized normal.
  void set_capture(bool on) { capture_ = on; }
  static std::vector<std::string> trace_names() { return {"radicand", "n_x", "n_y", "n_z"}; }
  // Test vectors: the words at the RTL unit's pins (rtl/normalize/normalize_unit.sv) —
  // in first, direct, the normal, ΔN_H and c; out the unit normal — in the block's format.
  VectorLayout vector_layout() const;
  void vector_in(const SpanPacket& p, int i, uint64_t* words) const;
  void vector_out(const SpanPacket& p, int i, uint64_t* words) const;
  void trace(const SpanPacket& p, int i, double* out) const {
    out[0] = radicand_[i];
    for (int c = 0; c < 3; ++c) out[1 + c] = p.n[c][i];
  }

 private:
  template <class T> void normalize_as(SpanPacket& p, bool direct);
  uint64_t word(float v) const;  // v at the pins: the format's raw word, or float32 bits

  NormalizeMode mode_;
  uint16_t seeded_[kSpanMax];
  PacketTally<2> tally_;  // packets of mode_ (0); forward-difference mode's bump packets, radicand direct (1)
  NumberContext numbers_;
  uint64_t nonfinite_ = 0;
  bool capture_ = false;
  float radicand_[kSpanMax] = {};
  int64_t raw_out_[3][kSpanMax] = {};  // fixed point: the last packet's results, as raw words (vectors)
};

}  // namespace shadetlm::modules
