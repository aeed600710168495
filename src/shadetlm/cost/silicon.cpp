#include "shadetlm/cost/silicon.hpp"

#include <algorithm>

namespace shadetlm::cost {
namespace {

uint64_t count_of(const modules::Ops& ops, Operation op) {
  switch (op) {
    case Operation::Add: return ops.add;
    case Operation::Mul: return ops.mul;
    case Operation::Div: return ops.div;
    case Operation::Sqrt: return ops.sqrt;
    case Operation::Rsqrt: return ops.rsqrt;
  }
  return 0;
}

}  // namespace

BlockSilicon block_silicon(const modules::Ops& ops, uint64_t work_cycles, const core::NumberFormat& format,
                           const std::string& setting) {
  BlockSilicon s;
  s.unpriced_ops = ops.lut + ops.fetch;
  for (size_t k = 0; k < std::size(kOperations); ++k) {
    const uint64_t n = count_of(ops, kOperations[k]);
    if (n == 0) continue;
    const std::optional<OperatorCost> c = operation_cost(kOperations[k], format);
    if (!c) {
      s.why = format.name() + " (" + setting + ") is a " + std::to_string(word_bits(format)) +
              "-bit word: the operators are priced up to " + std::to_string(kMaxPricedBits) + " bits";
      return s;
    }
    const uint64_t cycles = std::max<uint64_t>(work_cycles, 1);
    s.units[k] = std::max<uint64_t>((n + cycles - 1) / cycles, 1);  // ⌈n / cycles⌉, exact in integers
    s.area_um2 += double(s.units[k]) * c->area_um2;
    s.energy_pj += double(n) * c->energy_pj;
  }
  s.priced = true;
  return s;
}

}  // namespace shadetlm::cost
