#pragma once
// The normalize block's settings, pipeline.normalize.<key> (core/setting_fields.hpp).
#include "shadetlm/core/setting_fields.hpp"
#include "shadetlm/modules/normalize/normalize_kernel.hpp"

namespace shadetlm::modules {

struct NormalizeSettings {
  static constexpr const char* block = "normalize";
  NormalizeMode mode = NormalizeMode::Exact;
  RadicandSeed seed = RadicandSeed::Packet;
  enum class Impl { Kernel, Rtl } impl = Impl::Kernel;

  template <class F>
  void fields(F& f) {
    f(mode, "mode", normalize_mode_names(), "how the normal is normalized");
    f(seed, "seed", radicand_seed_names(),
      "forward-difference mode: the radicand seeded at every packet, or once per raster line and carried from "
      "packet to packet (docs/pipeline.md)");
    f(impl, "impl", {"kernel", "rtl"}, "the C++ kernel, or the RTL unit verilated into the loop (docs/rtl.md)");
  }
};

}  // namespace shadetlm::modules
