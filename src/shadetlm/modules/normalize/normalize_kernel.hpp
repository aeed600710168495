#pragma once
// Normalization of the interpolated normal, in five variants (normal-increments paper,
// formulas (13)–(16), and the fast inverse square roots a designer would weigh):
//
//   exact               r = x² + y² + z²; N · (1 / sqrt(r))
//   forward-difference  r by second-order differences along the packet:
//                         R_0 = |N_0|², δ_0 = 2 N_0·ΔN_H + |ΔN_H|², R_{n+1} = R_n + δ_n,
//                         δ_{n+1} = δ_n + c, c = 2|ΔN_H|² (from setup);
//                       two additions per pixel and no multiplication, then N · rsqrt(r);
//                       seeded at every packet (seed=packet), or once per raster line
//                       of a triangle and carried from packet to packet (seed=line),
//                       over a gap of k hidden pixels in one jump:
//                         R_{n+k} = R_n + k·δ_n + k(k−1)/2·c, δ_{n+k} = δ_n + k·c;
//                       a bump-mapped packet, whose normals do not step by ΔN_H, takes
//                       r direct into the same rsqrt unit
//   rsqrt0|1|2          r direct; the bit-level inverse square root estimate
//                       (one table-like look-up) refined by 0, 1 or 2 Newton steps
//                       y ← y (3/2 − r/2 · y²)
//
// The kernels are templates over the number type, so that a testbench can run them on
// Counted<float> and check the operation counts declared here.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "shadetlm/numeric/number.hpp"
#include "shadetlm/tlm/kernel_parts.hpp"
#include "shadetlm/tlm/packet.hpp"
#include "shadetlm/trace/test_vectors.hpp"

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

// An integer (a counter's) times a value of the datapath, rounded once to T.
template <class T>
T times_integer(int64_t k, T x) {
  return T(double(k) * double(x));
}
template <class T>
Counted<T> times_integer(int64_t k, Counted<T> x) {
  tally_counted<T>(Ops{0, /*mul*/ 1});
  return T(double(k) * double(x.v));
}

// |N_n|² along a span N_n = N_0 + n·ΔN_H by second-order differences (formulas
// (13)–(16)): R_n and δ_n at the next pixel.
template <class T>
struct RadicandState {
  T r, delta;
  // The seed at N_0: R_0 = |N_0|², δ_0 = 2 N_0·ΔN_H + c/2 (8 multiplications, 5 additions).
  static RadicandState seed(const T n0[3], const T dh[3], T c) {
    return {radicand(n0), T(2.0f) * (n0[0] * dh[0] + n0[1] * dh[1] + n0[2] * dh[2]) + T(0.5f) * c};
  }
  T next(T c) {  // R_n, then advances to R_{n+1}: two additions
    const T now = r;
    r = r + delta;
    delta = delta + c;
    return now;
  }
  // k > 0 pixels at once, over hidden pixels: 3 multiplications, 3 additions. k and
  // k(k−1)/2 come from the gap counter, integers: each product has one integer operand
  // and is rounded once to the format (times_integer), as a multiplier taking the
  // counter's bits would.
  void jump(int k, T c) {
    const int64_t steps = int64_t(k) * (k - 1) / 2;
    r = r + times_integer(k, delta) + times_integer(steps, c);
    delta = delta + times_integer(k, c);
  }
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
// Forward-difference mode starts from `carried` (R and δ at nx[0]) when given, else
// seeds at nx[0]; it leaves in `carried` the state after the span. With `reseed_at`, a
// carried radicand that reaches zero or below at pixel k (rounding carried along a long
// line between near-opposite normals: |N|² itself never does) is dropped there and the
// sequence seeded at N_k instead, once a span, and *reseed_at = k: the guard is R's sign
// bit, a wire.
template <class T>
void normalize_span(T* nx, T* ny, T* nz, int count, const T dh[3], T c, NormalizeMode mode, bool direct = false,
                    RadicandState<T>* carried = nullptr, int* reseed_at = nullptr) {
  if (mode == NormalizeMode::ForwardDifference && direct)
    return normalize_pixels<NormalizeMode::ForwardDifference>(nx, ny, nz, count);
  if (mode == NormalizeMode::ForwardDifference) {
    if (count == 0) return;
    const T n0[3] = {nx[0], ny[0], nz[0]};
    // The radicands first (a chain of additions), then the scaling in a straight loop
    // of its own, which vectorizes.
    RadicandState<T> radicands = carried ? *carried : RadicandState<T>::seed(n0, dh, c);
    T r[kSpanMax];
    for (int i = 0; i < count; ++i) {
      r[i] = radicands.next(c);
      if (reseed_at && *reseed_at < 0 && !(r[i] > T(0.0f))) {
        const T ni[3] = {nx[i], ny[i], nz[i]};
        radicands = RadicandState<T>::seed(ni, dh, c);
        r[i] = radicands.next(c);
        *reseed_at = i;
      }
    }
    if (carried) *carried = radicands;
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

// Operations per pixel and per packet (span), as the code above performs them; with
// `rsqrt_unit` (float16, fixed point) forward-difference mode's 1/√r is one rsqrt, else
// (float32) a square root and a division.
Ops normalize_ops_per_pixel(NormalizeMode mode, bool rsqrt_unit = false);
Ops normalize_ops_per_span(NormalizeMode mode);
// Forward-difference mode with seed=line: a packet that continues its raster line after
// hidden pixels jumps the carried radicand (RadicandState::jump).
Ops normalize_ops_per_jump();

// Where the forward-difference radicand starts a packet.
enum class RadicandSeed { Packet, Line };
const std::vector<std::string>& radicand_seed_names();  // "packet", "line"
// Forward-difference mode's bump packets: the radicand direct, then the rsqrt unit.
Ops normalize_ops_per_pixel_direct_rsqrt(bool rsqrt_unit = false);

class NormalizeKernel {
 public:
  static constexpr unsigned optional = Optional::numbers | Optional::details | Optional::vectors;  // (tlm/kernel_parts.hpp)
  // The radicand and inverse square root datapaths are of `format`
  // (pipeline.normalize.format).
  explicit NormalizeKernel(NormalizeMode mode, core::NumberFormat format = {}, RadicandSeed seed = RadicandSeed::Packet)
      : mode_(mode), seed_(seed), numbers_(format) {}
  void process(SpanPacket& p);
  Ops ops() const;
  NormalizeMode mode() const { return mode_; }
  // A pixel a cycle; the forward-difference radicand's seed (R0, δ0: 8 multiplications,
  // 5 additions) or jump (3, 3) takes the multipliers a cycle before the packet's first
  // pixel; a packet that continues its line where the last one ended needs neither.
  // A re-seed at pixel k (seed=line's guard) takes them a cycle before pixel k.
  Work work(const SpanPacket&) const {
    if (reseed_at_ >= 0) return Work{reseeded_, 0};
    return Work{nullptr, 1, nullptr, mode_ == NormalizeMode::ForwardDifference && start_ != Start::Carry ? 1u : 0u};
  }
  bool bypass(const SpanPacket&) const { return false; }
  NumberStats numbers() const { return {numbers_.format.name(), nonfinite_, numbers_.events}; }
  // Pixels and packets normalized (in either engine), (forward-difference mode) radicands
  // seeded (re-seeds included) and jumped, carried radicands dropped for a re-seed
  // (seed=line: one reached zero or below; its R, two additions, computed in vain), and
  // the pixels taking the radicand direct there (bump packets).
  nlohmann::json details() const {
    return {{"pixels", tally_.pixels[0] + tally_.pixels[1]}, {"packets", tally_.packets[0] + tally_.packets[1]},
            {"seeds", seeds_}, {"jumps", jumps_}, {"reseeds", reseeds_}, {"direct_pixels", tally_.pixels[1]}};
  }
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

  // How the last packet's radicand started (forward-difference mode): seeded, jumped over
  // hidden pixels of its line, or carried on from the pixel before.
  enum class Start { Seed, Jump, Carry };
  Start start_of(const SpanPacket& p, bool direct) const;
  // seed=line: the raster line the carried radicand belongs to, and R, δ at next_x.
  struct Line {
    bool open = false;
    uint32_t triangle = 0;
    int y = 0, next_x = 0;
    double r = 0, delta = 0;  // (holds float16's, float32's and fixed:I.F's values exactly: I + F ≤ 52)
  };

  NormalizeMode mode_;
  RadicandSeed seed_;
  Start start_ = Start::Seed;
  Line line_;
  uint64_t seeds_ = 0, jumps_ = 0, reseeds_ = 0;  // forward-difference packets seeded, jumped, re-seeded
  uint16_t reseeded_[kSpanMax];  // the last packet's work when it was re-seeded (reseed_at_ ≥ 0)
  int reseed_at_ = -1;           // the pixel the last packet was re-seeded at, or −1
  PacketTally<2> tally_;  // packets of mode_ (0); forward-difference mode's bump packets, radicand direct (1)
  NumberContext numbers_;
  uint64_t nonfinite_ = 0;
  bool capture_ = false;
  float radicand_[kSpanMax] = {};
  int64_t raw_out_[3][kSpanMax] = {};  // fixed point: the last packet's results, as raw words (vectors)
};

}  // namespace shadetlm::modules
