#pragma once
// Colour intensity (bump-mapping paper, Fig. 1): Blinn-Phong with every light of the
// scene and the material's colours, branch-free per pixel as a datapath computes it:
//
//   C = ambient ⊙ k_a ⊙ tex + Σ_lights radiance ⊙ (k_d ⊙ tex · max(0, N·L)
//                                                 + k_s · [N·L > 0] max(0, N·H)^shininess)
//
// L and H come from vector_interp where they vary over the frame, else they are the
// frame's constants. The power is one table look-up in hardware; in float32 here it is
// specular_power (power.hpp), in the reduced formats the exact power rounded once.
#include <algorithm>
#include <string>
#include <vector>

#include "shadetlm/numeric/number.hpp"
#include "shadetlm/tlm/kernel_parts.hpp"
#include "shadetlm/tlm/packet.hpp"

namespace shadetlm::modules {

class LightingKernel {
 public:
  static constexpr unsigned optional = Optional::numbers;  // (tlm/kernel_parts.hpp)
  // Its datapaths are of `format` (pipeline.lighting.format); the colour leaves as float32.
  explicit LightingKernel(const core::Scene& scene, core::NumberFormat format = {});

  void process(SpanPacket& p);
  Ops ops() const;
  // A light a cycle; with none, the ambient term alone takes one.
  Work work(const SpanPacket&) const { return {nullptr, uint32_t(std::max<size_t>(lights_.size(), 1))}; }
  bool bypass(const SpanPacket&) const { return false; }
  NumberStats numbers() const { return {numbers_.format.name(), nonfinite_, numbers_.events, checks_}; }

  Ops ops_per_pixel(bool textured) const;
  Ops ops_per_span() const;

  // Waveforms: N·L and N·H of the first light, the intensity (colour) out.
  void set_capture(bool on) { capture_ = on; }
  static std::vector<std::string> trace_names() { return {"n_dot_l", "n_dot_h", "r", "g", "b"}; }
  void trace(const SpanPacket& p, int i, double* out) const {
    out[0] = captured_[0][i], out[1] = captured_[1][i];
    for (int c = 0; c < 3; ++c) out[2 + c] = p.rgb[c][i];
  }

 private:
  struct Light {
    float radiance[3];
    bool l_varies, h_varies;      // read from the packet, else the constants below
    float l[3], h[3];
  };
  template <class T> void shade(SpanPacket& p);

  std::vector<Light> lights_;
  float ambient_[3];
  PacketTally<2> tally_;  // packets without (0) and with (1) a colour texture
  bool capture_ = false;
  float captured_[2][kSpanMax] = {};
  NumberContext numbers_;
  bool checks_;  // counts its non-finite outputs (checks_outputs: products and sums of bounded values)
  uint64_t nonfinite_ = 0;
};

}  // namespace shadetlm::modules
