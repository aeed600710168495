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

// `ops` done in `work_cycles` (the cycles the block computed in, by the timing model) in
// `format`: a unit of each kind for every operation of it a cycle needs, rounded up (at
// least one where it does any: a root every 8 pixels still needs its unit), so a block
// that spends more cycles on an item (a light a cycle, a tracer's iteration a cycle)
// shares its units over them; the energy of every operation counted. `setting` names the
// format's setting for `why`.
BlockSilicon block_silicon(const modules::Ops& ops, uint64_t work_cycles, const core::NumberFormat& format,
                           const std::string& setting);

}  // namespace shadetlm::cost
