#pragma once
// A block's silicon from what it counted (docs/silicon.md): the operators it needs to
// keep its II, their area, and the energy of the operations it did.
#include <cstdint>
#include <iterator>
#include <string>

#include "shadetlm/core/number_format.hpp"
#include "shadetlm/cost/operator_cost.hpp"
#include "shadetlm/numeric/ops.hpp"

namespace shadetlm::cost {

struct BlockSilicon {
  bool priced = false;  // false: its format has no figure (`why` says which and why)
  std::string why;
  uint64_t units[std::size(kOperations)] = {};  // operators of each kind (kOperations' order)
  double area_um2 = 0;  // of those operators
  double energy_pj = 0;  // of the frame's operations through them
  uint64_t unpriced_ops = 0;  // table reads and texel fetches: no figure yet
};

// `ops` done over `items` (the pixels, or triangles, its II is for) in `format`: a unit of
// each kind for every operation of it an item needs within the II cycles, rounded up
// (an operation a span of 8 pixels still needs its unit); the energy of every
// operation counted. `setting` names the format's setting for `why`.
BlockSilicon block_silicon(const modules::Ops& ops, uint64_t items, int ii, const core::NumberFormat& format,
                           const std::string& setting);

}  // namespace shadetlm::cost
