// The normal multiplexer's declaration (tlm/block.hpp).
#include "shadetlm/tlm/block.hpp"
#include "shadetlm/modules/normal_mux/normal_mux_kernel.hpp"

namespace shadetlm::modules {

BlockDecl normal_mux_block() {
  return {"normal_mux", {1, 1}, false, {}, NormalMuxKernel::needed, [](const BlockContext&) -> std::unique_ptr<Block> {
            return std::make_unique<SpanBlock<NormalMuxKernel>>();
          }};
}

}  // namespace shadetlm::modules
