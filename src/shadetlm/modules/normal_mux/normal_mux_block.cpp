// The normal multiplexer's declaration (tlm/block.hpp).
#include "shadetlm/tlm/block.hpp"
#include "shadetlm/modules/normal_mux/normal_mux_kernel.hpp"

namespace shadetlm::modules {

BlockDecl normal_mux_block() {
  BlockDecl d = declare("normal_mux");
  d.basics.timing = {1, 1};
  d.needed = NormalMuxKernel::needed;
  d.make = [](const BlockContext&) -> std::unique_ptr<Block> { return std::make_unique<SpanBlock<NormalMuxKernel>>(); };
  return d;
}

}  // namespace shadetlm::modules
