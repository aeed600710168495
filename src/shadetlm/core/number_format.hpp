#pragma once
// The number format of a datapath (docs/numerical-stability.md), as the scene's pipeline
// section names it:
//
//   float32        IEEE binary32, the default
//   float16        IEEE binary16: 11-bit significand, exponents 2^-14 … 2^15, subnormals
//                  down to 2^-24; overflow gives ±infinity
//   fixed:I.F      two's complement with a sign bit, I integer bits and F fraction bits:
//                  values k·2^-F in [−2^I, 2^I − 2^-F]; results round to nearest and
//                  saturate at the ends (each saturation is counted)
//
// "default" (a block's setting only) takes pipeline.number_format.
#include <string>

namespace shadetlm::core {

struct NumberFormat {
  enum class Kind { Float32, Float16, Fixed };
  Kind kind = Kind::Float32;
  int int_bits = 0, frac_bits = 0;  // fixed point only

  // Limits of fixed:I.F — I + F ≤ 52 keeps every value exact in a double and every
  // product within 128 bits.
  static constexpr int kMaxIntBits = 30, kMaxFracBits = 48, kMaxBits = 52;

  static NumberFormat fixed(int int_bits, int frac_bits) { return {Kind::Fixed, int_bits, frac_bits}; }
  // Parses a format name; throws std::invalid_argument saying what is wrong.
  static NumberFormat parse(const std::string& name);
  std::string name() const;
  bool operator==(const NumberFormat& o) const {
    return kind == o.kind && int_bits == o.int_bits && frac_bits == o.frac_bits;
  }
  bool operator!=(const NumberFormat& o) const { return !(*this == o); }
};

}  // namespace shadetlm::core
