#pragma once
// Operation counts by kind — the cost figures the papers' claims are about — and
// Counted<T>, a number type that counts every operation done on it, so that a
// testbench can check a kernel's declared counts against what its code really does.
#include <cmath>
#include <cstdint>
#include <type_traits>

#include <nlohmann/json.hpp>

namespace shadetlm::modules {

struct Ops {
  uint64_t add = 0, mul = 0, div = 0, sqrt = 0, rsqrt = 0, lut = 0, fetch = 0;
  uint64_t line = 0;  // memory lines read by the texture unit (a cost, not arithmetic)

  // Inlined always: a tracer adds a constant a step, whose zero kinds then cost nothing
  // (as a call, GCC's choice in the tracers, it was 18 instructions a step).
  [[gnu::always_inline]] constexpr Ops& operator+=(const Ops& o) {
    add += o.add; mul += o.mul; div += o.div; sqrt += o.sqrt; rsqrt += o.rsqrt; lut += o.lut;
    fetch += o.fetch; line += o.line;
    return *this;
  }
  constexpr Ops operator+(const Ops& o) const { return Ops(*this) += o; }
  constexpr Ops operator*(uint64_t n) const {
    return {add * n, mul * n, div * n, sqrt * n, rsqrt * n, lut * n, fetch * n, line * n};
  }
  bool operator==(const Ops& o) const {
    return add == o.add && mul == o.mul && div == o.div && sqrt == o.sqrt && rsqrt == o.rsqrt &&
           lut == o.lut && fetch == o.fetch && line == o.line;
  }
  // Operations of the datapaths and fetches (memory lines are not operations).
  uint64_t total() const { return add + mul + div + sqrt + rsqrt + lut + fetch; }
  nlohmann::json to_json() const {
    return {{"add", add}, {"mul", mul}, {"div", div}, {"sqrt", sqrt},
            {"rsqrt", rsqrt}, {"lut", lut}, {"fetch", fetch}, {"line", line}};
  }
};

// The packets of a block whose operations are so many per pixel and so many per packet,
// for a few kinds of packet (a mode; textured or not): each packet adds its pixels to
// its kind's count, and the block forms its operations when they are read. (Multiplying
// eight 64-bit counts on every packet cost about 5 instructions a pixel on short spans.)
template <int Kinds>
struct PacketTally {
  uint64_t pixels[Kinds] = {}, packets[Kinds] = {};  // packets: those with pixels
  void add(int kind, int count) {
    pixels[kind] += uint64_t(count);
    packets[kind] += count > 0 ? 1 : 0;
  }
};

// Counted<T>: T with every arithmetic operation tallied in Counted<T>::ops.
// Subtraction counts as an add, comparisons and negation are free (as in hardware,
// where they are wiring or a sign flip).
template <class T>
struct Counted {
  T v{};
  static inline Ops ops{};

  Counted() = default;
  Counted(T x) : v(x) {}  // NOLINT: constants mix freely, as with T
  template <class U, class = std::enable_if_t<std::is_arithmetic_v<U>>>
  explicit operator U() const { return U(v); }

  friend Counted operator+(Counted a, Counted b) { ++ops.add; return a.v + b.v; }
  friend Counted operator-(Counted a, Counted b) { ++ops.add; return a.v - b.v; }
  friend Counted operator*(Counted a, Counted b) { ++ops.mul; return a.v * b.v; }
  friend Counted operator/(Counted a, Counted b) { ++ops.div; return a.v / b.v; }
  friend Counted operator-(Counted a) { return -a.v; }
  Counted& operator+=(Counted b) { return *this = *this + b; }
  Counted& operator-=(Counted b) { return *this = *this - b; }
  Counted& operator*=(Counted b) { return *this = *this * b; }
  friend bool operator<(Counted a, Counted b) { return a.v < b.v; }
  friend bool operator>(Counted a, Counted b) { return a.v > b.v; }
  friend bool operator<=(Counted a, Counted b) { return a.v <= b.v; }
  friend bool operator>=(Counted a, Counted b) { return a.v >= b.v; }
  friend bool operator==(Counted a, Counted b) { return a.v == b.v; }
  friend bool operator!=(Counted a, Counted b) { return a.v != b.v; }
  Counted& operator/=(Counted b) { return *this = *this / b; }
  // The integer part, wiring: found by a template's unqualified floor(x) after
  // `using std::floor` (core's height and volume reads, run counted by the tracer's check;
  // core knows no number formats). The modules' kernels call floor_op (number.hpp),
  // which the formats overload too.
  friend Counted floor(Counted a) { return std::floor(a.v); }
};

// The elementary functions of the datapaths, for plain floating types and Counted.
template <class T> T sqrt_op(T x) { return std::sqrt(x); }
template <class T> T rsqrt_op(T x) { return T(1) / std::sqrt(x); }
template <class T> T pow_op(T x, T e) { return std::pow(x, e); }
template <class T> T max_op(T a, T b) { return a > b ? a : b; }
template <class T> Counted<T> sqrt_op(Counted<T> x) { ++Counted<T>::ops.sqrt; return std::sqrt(x.v); }
// (Counted<float> computes float32's 1 / √x: a square root and a division, as counted;
// float16 and fixed point have a correctly rounded rsqrt_op of their own, not counted here)
template <class T> Counted<T> rsqrt_op(Counted<T> x) { ++Counted<T>::ops.sqrt, ++Counted<T>::ops.div; return T(1) / std::sqrt(x.v); }
// The specular power is one table look-up in hardware (it is powf here).
template <class T> Counted<T> pow_op(Counted<T> x, Counted<T> e) { ++Counted<T>::ops.lut; return std::pow(x.v, e.v); }
template <class T> Counted<T> pow_op(Counted<T> x, float e) { ++Counted<T>::ops.lut; return std::pow(x.v, T(e)); }
// The texture unit's LOD (log2) and EWA weight (exp): one table look-up each.
template <class T> T log2_op(T x) { return std::log2(x); }
template <class T> T exp_op(T x) { return std::exp(x); }
template <class T> Counted<T> log2_op(Counted<T> x) { ++Counted<T>::ops.lut; return std::log2(x.v); }
template <class T> Counted<T> exp_op(Counted<T> x) { ++Counted<T>::ops.lut; return std::exp(x.v); }

// Adds operations done outside T (e.g. on the bits of a float) to T's tally.
template <class T> void tally_counted(const Ops& o) { Counted<T>::ops += o; }

// Whether T is a Counted type.
template <class T> struct is_counted : std::false_type {};
template <class U> struct is_counted<Counted<U>> : std::true_type {};
// Operations the hardware does whose result the model need not compute (a select
// discards it): tallied on a Counted type, nothing on the others. Only the arithmetic:
// fetches and lines are a block's own tally, never the number type's.
template <class T> void count_discarded(Ops o) {
  if constexpr (is_counted<T>::value) {
    o.fetch = o.line = 0;
    T::ops += o;
  }
}

// The value of a number of any of these types, as a plain T.
template <class T> T value(T x) { return x; }
template <class T> T value(Counted<T> x) { return x.v; }

// x times a constant power of two (½, ¼, 1/256: known when the unit is built): an
// exponent shift in hardware (a wire shift in fixed point), not an operation. Every datapath follows this rule: a division by a texture's
// power-of-two size, the tracers' midpoints and EWA's half-axes alike.
template <class T>
T shifted(T x, T power_of_two) {
  if constexpr (is_counted<T>::value) return T(value(x) * value(power_of_two));
  else return x * power_of_two;
}

}  // namespace shadetlm::modules
