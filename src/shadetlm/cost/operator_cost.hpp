#pragma once
// The silicon of one operation: its area and its energy in standard cells of the OSU
// 0.18 µm library at 1.8 V (docs/silicon.md). Fixed-point operations are priced by the
// power laws scripts/operators.py fitted to the operators it synthesized through the
// flow; floating-point ones are built from those operators (docs/silicon.md says how).
#include <optional>
#include <string>

#include "shadetlm/core/number_format.hpp"

namespace shadetlm::cost {

// The node and the conditions every figure is for.
inline constexpr const char* kNode = "OSU 0.18 um standard cells (osu018), 1.8 V";
inline constexpr double kActivity = 0.5;  // each input bit's transitions a cycle (random data)
// The widest word a power law is taken to (they are fitted over the words
// scripts/operators.py synthesized, 8 to 24 bits, and extrapolated outside them).
inline constexpr int kMaxPricedBits = 32;

struct OperatorCost {
  double area_um2 = 0, energy_pj = 0;  // of one unit; of one operation through it
  OperatorCost& operator+=(const OperatorCost& o) {
    area_um2 += o.area_um2, energy_pj += o.energy_pj;
    return *this;
  }
  OperatorCost operator*(double n) const { return {area_um2 * n, energy_pj * n}; }
};

// The operations the model counts (modules::Ops) that have a figure.
enum class Operation { Add, Mul, Div, Sqrt, Rsqrt };
inline constexpr Operation kOperations[] = {Operation::Add, Operation::Mul, Operation::Div, Operation::Sqrt,
                                            Operation::Rsqrt};
const char* name_of(Operation op);

// An operator of the synthesized set at a word of `bits` (e.g. "add_sat", 14).
OperatorCost synthesized(const std::string& op, double bits);

// One operation in a number format; nothing where the format's word is wider than
// kMaxPricedBits (no figure: the power laws are not taken that far).
std::optional<OperatorCost> operation_cost(Operation op, const core::NumberFormat& format);

// The word of a format: 1 + I + F bits for fixed:I.F (its sign), 32 or 16 for floats.
int word_bits(const core::NumberFormat& format);

}  // namespace shadetlm::cost
