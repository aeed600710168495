#pragma once
// The number types of the datapaths (docs/numerical-stability.md): float (float32),
// Half (float16) and Fixed (fixed:I.F). The kernels are templates over the type, so
// each algorithm is written once and runs in every format; a block picks its format
// (pipeline.<block>.format) and runs its kernel with with_number_type().
//
// Half and Fixed compute each operation exactly (in double) and round the result once
// to their format, as a hardware unit of that width would:
//   Half   round to nearest even; beyond 65504 the result is ±infinity (IEEE)
//   Fixed  round to nearest — products ties up (the half-LSB adder of a multiplier),
//          quotients ties away from zero, conversions and the elementary functions
//          ties to even — and results beyond the format saturate to its largest or
//          smallest value
// The events that a designer must know about are counted per block: overflows (a
// saturation, or an infinite result from finite operands) and invalid operations (a
// NaN from non-NaN operands, a division by zero or a square root of a negative in fixed
// point). The formats of the block running are held in a NumberContext the block owns;
// the model runs on one thread, so the context in force is a plain global. An event is
// counted each time it happens: a constant that saturates when a block rounds it to its
// format (once per packet, or per pixel) counts every time.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <algorithm>
#include <stdexcept>
#include <string>

#include "shadetlm/core/number_format.hpp"
#include "shadetlm/numeric/ops.hpp"

namespace shadetlm::modules {

struct NumberEvents {
  uint64_t overflows = 0;  // saturated (fixed) or infinite from finite operands (float16)
  uint64_t invalid = 0;    // NaN produced (float16); 0/0, x/0, sqrt(−x) or NaN converted in (fixed)
  Ops counted;             // with count_float32_operations: what the kernel's number type did
};

// Testbenches only: float32 datapaths run on Counted<float> instead of float (the same
// arithmetic, but the specular power by std::pow and no vector lanes), each block's
// operations tallied in its context (NumberEvents::counted), so that a test can hold
// them against the counts the kernels declare (testbenches/test_numbers.cpp).
inline bool count_float32_operations = false;

struct NumberContext {
  core::NumberFormat format;
  int frac_bits = 16;
  int64_t max_raw = 0, min_raw = 0;  // 2^(I+F) − 1 and −2^(I+F)
  double scale = 1, inv_scale = 1;   // 2^F and 2^-F
  NumberEvents events;

  explicit NumberContext(core::NumberFormat f = {}) : format(f) {
    if (f.kind != core::NumberFormat::Kind::Fixed) return;
    if (f.int_bits < 0 || f.frac_bits < 1 || f.int_bits + f.frac_bits > core::NumberFormat::kMaxBits)
      throw std::invalid_argument("fixed-point format out of range: " + f.name());
    frac_bits = f.frac_bits;
    max_raw = (int64_t(1) << (f.int_bits + f.frac_bits)) - 1;
    min_raw = -max_raw - 1;
    scale = std::ldexp(1.0, f.frac_bits);
    inv_scale = std::ldexp(1.0, -f.frac_bits);
  }
};

// The context of the block running (set by NumberScope).
inline NumberContext* number_context = nullptr;

class NumberScope {
 public:
  explicit NumberScope(NumberContext& c) : saved_(number_context) { number_context = &c; }
  ~NumberScope() { number_context = saved_; }
  NumberScope(const NumberScope&) = delete;
  NumberScope& operator=(const NumberScope&) = delete;

 private:
  NumberContext* saved_;
};

// x rounded to the nearest binary16 value (ties to even), as a double: ±infinity past
// the largest finite value, subnormals below 2^-14, NaN kept.
inline double round_to_half(double x) {
  if (!std::isfinite(x) || x == 0) return x;
  const int e = std::max(std::ilogb(x), -14);  // the binade; subnormals share 2^-14's quantum
  const double quantum = std::ldexp(1.0, e - 10);
  const double r = std::nearbyint(x / quantum) * quantum;  // exact scaling, round to even
  return std::abs(r) > 65504.0 ? std::copysign(HUGE_VAL, x) : r;
}

class Half {
 public:
  Half() = default;
  Half(double x) : v_(round_to_half(x)) { note(x); }  // NOLINT: constants mix freely, as with float
  Half(float x) : Half(double(x)) {}                  // NOLINT
  Half(int x) : Half(double(x)) {}                    // NOLINT
  explicit operator float() const { return float(v_); }
  explicit operator double() const { return v_; }

  friend Half operator+(Half a, Half b) { return result(a.v_ + b.v_, a, b); }
  friend Half operator-(Half a, Half b) { return result(a.v_ - b.v_, a, b); }
  friend Half operator*(Half a, Half b) { return result(a.v_ * b.v_, a, b); }
  friend Half operator/(Half a, Half b) { return result(a.v_ / b.v_, a, b); }
  friend Half operator-(Half a) { return raw(-a.v_); }
  Half& operator+=(Half b) { return *this = *this + b; }
  Half& operator-=(Half b) { return *this = *this - b; }
  Half& operator*=(Half b) { return *this = *this * b; }
  friend bool operator<(Half a, Half b) { return a.v_ < b.v_; }
  friend bool operator>(Half a, Half b) { return a.v_ > b.v_; }
  friend bool operator<=(Half a, Half b) { return a.v_ <= b.v_; }
  friend bool operator>=(Half a, Half b) { return a.v_ >= b.v_; }
  friend bool operator==(Half a, Half b) { return a.v_ == b.v_; }

  static Half raw(double exact) { Half h; h.v_ = exact; return h; }  // already a binary16 value
  // The result x of an operation on a and b: a NaN from non-NaN operands is counted
  // (a NaN coming in is the operand's event, counted where it arose).
  static Half result(double x, Half a, Half b) {
    if (number_context && !std::isfinite(x)) {
      if (std::isnan(x) && !std::isnan(a.v_) && !std::isnan(b.v_)) ++number_context->events.invalid;
      // Infinite already in double (x/0, rsqrt(0), a power past double's range): an
      // overflow (the constructor counts the finite results rounded to infinity).
      if (std::isinf(x) && std::isfinite(a.v_) && std::isfinite(b.v_)) ++number_context->events.overflows;
    }
    return x;
  }
  static Half result(double x, Half a) { return result(x, a, a); }

 private:
  // A finite value rounded to infinity: an overflow.
  void note(double x) {
    if (number_context && std::isinf(v_) && std::isfinite(x)) ++number_context->events.overflows;
  }
  double v_ = 0;
};

class Fixed {
 public:
  Fixed() = default;
  Fixed(double x) : raw_(from_double(x)) {}  // NOLINT: constants mix freely, as with float
  Fixed(float x) : Fixed(double(x)) {}       // NOLINT
  Fixed(int x) : Fixed(double(x)) {}         // NOLINT
  explicit operator double() const { return double(raw_) * number_context->inv_scale; }
  explicit operator float() const { return float(double(*this)); }
  int64_t raw() const { return raw_; }
  static Fixed from_raw(__int128 r) { Fixed f; f.raw_ = saturate(r); return f; }

  friend Fixed operator+(Fixed a, Fixed b) { return from_raw(__int128(a.raw_) + b.raw_); }
  friend Fixed operator-(Fixed a, Fixed b) { return from_raw(__int128(a.raw_) - b.raw_); }
  friend Fixed operator-(Fixed a) { return from_raw(-__int128(a.raw_)); }
  friend Fixed operator*(Fixed a, Fixed b) {
    const int f = number_context->frac_bits;
    const __int128 product = __int128(a.raw_) * b.raw_;  // 2F fraction bits
    return from_raw((product + (__int128(1) << (f - 1))) >> f);  // round half up
  }
  friend Fixed operator/(Fixed a, Fixed b) {
    if (b.raw_ == 0) {
      ++number_context->events.invalid;
      return from_raw(a.raw_ == 0 ? 0 : a.raw_ > 0 ? number_context->max_raw : number_context->min_raw);
    }
    const __int128 n = __int128(a.raw_) * (__int128(1) << number_context->frac_bits), d = b.raw_;
    __int128 q = n / d;
    const __int128 r = n % d;  // round to nearest, ties away from zero
    if (2 * (r < 0 ? -r : r) >= (d < 0 ? -d : d)) q += (n < 0) == (d < 0) ? 1 : -1;
    return from_raw(q);
  }
  Fixed& operator+=(Fixed b) { return *this = *this + b; }
  Fixed& operator-=(Fixed b) { return *this = *this - b; }
  Fixed& operator*=(Fixed b) { return *this = *this * b; }
  friend bool operator<(Fixed a, Fixed b) { return a.raw_ < b.raw_; }
  friend bool operator>(Fixed a, Fixed b) { return a.raw_ > b.raw_; }
  friend bool operator<=(Fixed a, Fixed b) { return a.raw_ <= b.raw_; }
  friend bool operator>=(Fixed a, Fixed b) { return a.raw_ >= b.raw_; }
  friend bool operator==(Fixed a, Fixed b) { return a.raw_ == b.raw_; }

 private:
  static int64_t saturate(__int128 r) {
    NumberContext& c = *number_context;
    if (r > c.max_raw) return ++c.events.overflows, c.max_raw;
    if (r < c.min_raw) return ++c.events.overflows, c.min_raw;
    return int64_t(r);
  }
  static int64_t from_double(double x) {
    NumberContext& c = *number_context;
    if (std::isnan(x)) return ++c.events.invalid, 0;
    const double r = std::nearbyint(x * c.scale);  // exact scaling, round to even
    if (!(std::abs(r) < 0x1p62)) return saturate(r > 0 ? c.max_raw + __int128(1) : c.min_raw - __int128(1));
    return saturate(int64_t(r));
  }
  int64_t raw_ = 0;
};

// The elementary functions in Half and Fixed: one correctly rounded unit each (the
// power is a table look-up in hardware).
inline Half sqrt_op(Half x) { return Half::result(std::sqrt(double(x)), x); }
inline Half rsqrt_op(Half x) { return Half::result(1.0 / std::sqrt(double(x)), x); }
// The exponent is the table's content, not a value of the datapath.
inline Half pow_op(Half x, float e) { return Half::result(std::pow(double(x), double(e)), x); }
// The fixed-point square roots are computed on the raw integers, correctly rounded (to
// nearest; no ties can occur), as the RTL unit does (rtl/normalize): a double's sqrt
// rounded again to F bits could be a unit off where the root lies near a half unit.
using uint128 = unsigned __int128;
// ⌊√v⌋ and v − ⌊√v⌋² for v < 2^126.
inline uint128 isqrt(uint128 v, uint128* remainder = nullptr) {
  uint128 s = uint128(std::sqrt(double(v)));
  while (s * s > v) --s;
  while ((s + 1) * (s + 1) <= v) ++s;
  if (remainder) *remainder = v - s * s;
  return s;
}
inline Fixed sqrt_op(Fixed x) {
  if (x < Fixed::from_raw(0)) return ++number_context->events.invalid, Fixed::from_raw(0);
  // √(x·2^-F)·2^F = √(x·2^F): round up where the remainder passes s (√v > s + ½).
  uint128 rem;
  const uint128 s = isqrt(uint128(x.raw()) << number_context->frac_bits, &rem);
  return Fixed::from_raw(__int128(rem > s ? s + 1 : s));
}
inline Fixed rsqrt_op(Fixed x) {
  if (!(x > Fixed::from_raw(0))) return ++number_context->events.invalid, Fixed::from_raw(number_context->max_raw);
  const int f = number_context->frac_bits;
  if (3 * f + 3 > 126) return 1.0 / std::sqrt(double(x));  // beyond 128-bit integers (F > 41): via double
  // 2^F / √(x·2^-F) = √(2^3F / x). With q, rq = 2^3F ÷ x and s, rem = ⌊√q⌋, q − s²: the
  // root passes s + ½ when rem > s, or rem = s and rq/x > ¼.
  const uint128 n = uint128(1) << (3 * f), d = uint128(x.raw());
  const uint128 q = n / d, rq = n % d;
  uint128 rem;
  const uint128 s = isqrt(q, &rem);
  const bool up = rem > s || (rem == s && 4 * rq > d);
  return Fixed::from_raw(__int128(std::min<uint128>(up ? s + 1 : s, uint128(number_context->max_raw) + 1)));
}
inline Fixed pow_op(Fixed x, float e) { return std::pow(double(x), double(e)); }

// floor(x): in fixed point, the fraction bits cleared (wiring).
template <class T> T floor_op(T x) { return std::floor(x); }
// (the integer part of a number: wiring, not an operation)
template <class T> Counted<T> floor_op(Counted<T> x) { return std::floor(x.v); }
inline Half floor_op(Half x) { return Half::raw(std::floor(double(x))); }
inline Fixed floor_op(Fixed x) {
  const int f = number_context->frac_bits;
  return Fixed::from_raw(__int128(x.raw() >> f) * (__int128(1) << f));
}

// Runs body(T{}) with T the number type of `context.format`, that context in force.
template <class Body>
void with_number_type(NumberContext& context, Body&& body) {
  switch (context.format.kind) {
    case core::NumberFormat::Kind::Float32:
      if (count_float32_operations) {
        Counted<float>::ops = {};
        body(Counted<float>{});
        context.events.counted += Counted<float>::ops;
        return;
      }
      body(float{});
      return;
    case core::NumberFormat::Kind::Float16: {
      NumberScope scope(context);
      body(Half{});
      return;
    }
    default: {
      NumberScope scope(context);
      body(Fixed{});
      return;
    }
  }
}

// Whether v is NaN or infinite (its exponent field all ones): a test on the bits, which
// vectorizes where std::isfinite's call or branch would not.
inline bool is_nonfinite(float v) {
  uint32_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  return (bits & 0x7f800000u) == 0x7f800000u;
}

// Non-finite values among n floats: a branch-free loop the compiler vectorizes, so that
// every block can count what it puts out at a small cost.
inline uint64_t count_nonfinite(const float* v, int n) {
  uint32_t bad = 0;
  for (int i = 0; i < n; ++i) bad += is_nonfinite(v[i]);
  return bad;
}

// The same over the first n columns of R rows (a packet's x, y, z or r, g, b arrays):
// one loop for all rows, so that a short span pays the loop's set-up once. (Blocks of 8
// columns with the ones past n masked off were tried: not vectorized, 60 % slower.)
template <size_t R, size_t N>
uint64_t count_nonfinite(const float (&rows)[R][N], int n) {
  uint32_t bad = 0;
  for (int i = 0; i < n; ++i)
    for (size_t r = 0; r < R; ++r) {
      uint32_t bits;
      std::memcpy(&bits, &rows[r][i], sizeof bits);
      bad += (bits & 0x7f800000u) == 0x7f800000u;
    }
  return bad;
}

// What a block reports of its numbers (BlockStats).
struct NumberStats {
  std::string format = "float32";
  uint64_t nonfinite = 0;  // NaN or infinite values among the block's outputs
  NumberEvents events;
  bool counted = true;     // false: the block does not test its outputs (see checks_outputs)
};

// Whether a block tests its outputs for NaN and infinity: always in a reduced format;
// in float32 only where a finite input can give a non-finite result — a division or a
// reciprocal square root (normalize, vector_interp, …). A float32 block that only adds
// and multiplies bounded values (the walker, lighting) passes on what it was given,
// counted where it arose; the test cost 43 instructions a pixel on the Phong path when
// every block made it (docs/numerical-stability.md), and the framebuffer catches all.
inline bool checks_outputs(const core::NumberFormat& format, bool divides) {
  return divides || format.kind != core::NumberFormat::Kind::Float32;
}

}  // namespace shadetlm::modules
