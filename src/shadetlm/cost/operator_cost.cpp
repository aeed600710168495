#include "shadetlm/cost/operator_cost.hpp"

#include <cmath>
#include <stdexcept>

namespace shadetlm::cost {
namespace {

struct PowerLaw {
  const char* op;
  double area_c, area_k, energy_c, energy_k;  // area µm² = c·W^k, energy pJ = c·W^k
};
constexpr PowerLaw kFits[] = {
#include "shadetlm/cost/operator_fits.inc"
};

// A float's significand (with its hidden bit) and exponent widths.
struct FloatShape {
  int significand, exponent;
};

// A barrel shifter of n bits: ⌈log2 n⌉ levels of n two-way selects.
OperatorCost shifter(int n) { return synthesized("mux", n) * std::ceil(std::log2(double(n))); }

// A float operation from the fixed-point operators (docs/silicon.md, "Floating point"):
// the significands' operation, the exponents' adder, the shifts that align and normalize.
// Rounding is in the operators (each rounds to nearest); special values are not priced.
// (1/√ is composed in operation_cost.)
OperatorCost float_cost(Operation op, FloatShape f) {
  const int m = f.significand, e = f.exponent;
  if (op == Operation::Add) {  // compare and subtract the exponents, align, add with 3
                               // guard bits, normalize, adjust the exponent
    OperatorCost c = synthesized("compare", e);
    c += synthesized("add", e) * 2;
    c += shifter(m + 3) * 2;
    c += synthesized("add", m + 3);
    return c;
  }
  // A product, quotient or root: the significands' operator, the exponents' adder (a
  // root's exponent is halved, wiring, after its bias is taken off), one bit of normalization.
  OperatorCost c = synthesized(op == Operation::Mul ? "mul" : op == Operation::Div ? "div" : "sqrt", m);
  c += synthesized("add", e);
  c += synthesized("mux", m);
  return c;
}

// A fixed-point operation of a W-bit word, as the model's type computes it: sums and
// products saturate; a division and a square root are priced unsaturated (docs/rtl.md,
// "Calibration").
OperatorCost fixed_cost(Operation op, int w) {
  return synthesized(op == Operation::Add ? "add_sat" : op == Operation::Mul ? "mul_sat"
                     : op == Operation::Div ? "div" : "sqrt", w);
}

}  // namespace

const char* name_of(Operation op) {
  switch (op) {
    case Operation::Add: return "add";
    case Operation::Mul: return "mul";
    case Operation::Div: return "div";
    case Operation::Sqrt: return "sqrt";
    case Operation::Rsqrt: return "rsqrt";
  }
  return "?";
}

OperatorCost synthesized(const std::string& op, double bits) {
  for (const PowerLaw& f : kFits)
    if (op == f.op) return {f.area_c * std::pow(bits, f.area_k), f.energy_c * std::pow(bits, f.energy_k)};
  throw std::invalid_argument("no synthesized operator " + op);
}

int word_bits(const core::NumberFormat& format) {
  switch (format.kind) {
    case core::NumberFormat::Kind::Float32: return 32;
    case core::NumberFormat::Kind::Float16: return 16;
    case core::NumberFormat::Kind::Fixed: return 1 + format.int_bits + format.frac_bits;
  }
  return 0;
}

std::optional<OperatorCost> operation_cost(Operation op, const core::NumberFormat& format) {
  if (op == Operation::Rsqrt) {  // a correctly rounded 1/√: a square root, then a division
    std::optional<OperatorCost> root = operation_cost(Operation::Sqrt, format), div = operation_cost(Operation::Div, format);
    if (!root || !div) return std::nullopt;
    *root += *div;
    return root;
  }
  switch (format.kind) {
    case core::NumberFormat::Kind::Float32: return float_cost(op, {24, 8});
    case core::NumberFormat::Kind::Float16: return float_cost(op, {11, 5});
    case core::NumberFormat::Kind::Fixed: {
      const int w = word_bits(format);
      if (w > kMaxPricedBits) return std::nullopt;
      return fixed_cost(op, w);
    }
  }
  return std::nullopt;
}

}  // namespace shadetlm::cost
