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
OperatorCost float_cost(Operation op, FloatShape f) {
  const int m = f.significand, e = f.exponent;
  switch (op) {
    case Operation::Add: {  // compare and subtract the exponents, align, add with 3 guard
                            // bits, normalize, adjust the exponent
      OperatorCost c = synthesized("compare", e);
      c += synthesized("add", e) * 2;
      c += shifter(m + 3) * 2;
      c += synthesized("add", m + 3);
      return c;
    }
    case Operation::Mul: {  // the significands' product, the exponents' sum, one bit of normalization
      OperatorCost c = synthesized("mul", m);
      c += synthesized("add", e);
      c += synthesized("mux", m);
      return c;
    }
    case Operation::Div: {
      OperatorCost c = synthesized("div", m);
      c += synthesized("add", e);
      c += synthesized("mux", m);
      return c;
    }
    case Operation::Sqrt: {  // the exponent halved (wiring) after its bias is taken off
      OperatorCost c = synthesized("sqrt", m);
      c += synthesized("add", e);
      c += synthesized("mux", m);
      return c;
    }
    case Operation::Rsqrt: {  // a square root, then a division (correctly rounded 1/√)
      OperatorCost c = float_cost(Operation::Sqrt, f);
      c += float_cost(Operation::Div, f);
      return c;
    }
  }
  throw std::logic_error("float_cost: an operation without a case");
}

// A fixed-point operation of a W-bit word, as the model's type computes it: sums and
// products saturate; a division and a square root are priced unsaturated; 1/√ is a
// square root and a division (docs/rtl.md, "Calibration").
OperatorCost fixed_cost(Operation op, int w) {
  switch (op) {
    case Operation::Add: return synthesized("add_sat", w);
    case Operation::Mul: return synthesized("mul_sat", w);
    case Operation::Div: return synthesized("div", w);
    case Operation::Sqrt: return synthesized("sqrt", w);
    case Operation::Rsqrt: {
      OperatorCost c = synthesized("sqrt", w);
      c += synthesized("div", w);
      return c;
    }
  }
  throw std::logic_error("fixed_cost: an operation without a case");
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
