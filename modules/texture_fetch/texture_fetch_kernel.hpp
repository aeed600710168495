#pragma once
// The texture unit, for the material's colour texture: perspective-correct uv
// (uv/w interpolated, times w), then a bilinear read of the finest level with the
// shared addressing convention (core/texture.hpp: texel centres, wrap modes). Packets
// of materials without a texture pass by untouched. Mip-mapping and the anisotropic
// filters arrive with the texturing issue; the golden model reads the same level.
#include <string>
#include <vector>

#include "modules/common/packet.hpp"

namespace modules {

class TextureFetchKernel {
 public:
  explicit TextureFetchKernel(const core::Scene& scene) : scene_(scene) {}
  static bool needed(const core::Scene& scene);

  void process(SpanPacket& p);
  const Ops& ops() const { return ops_; }
  uint64_t work(const SpanPacket& p) const { return uint64_t(p.count); }
  bool bypass(const SpanPacket& p) const { return p.tri->material->texture < 0; }

  // Waveforms: uv, the texel address (x, y of the bilinear footprint's first texel)
  // and the filtered colour.
  void set_capture(bool on) { capture_ = on; }
  static std::vector<std::string> trace_names() { return {"u", "v", "texel_x", "texel_y", "r", "g", "b"}; }
  void trace(const SpanPacket& p, int i, double* out) const {
    for (int c = 0; c < 4; ++c) out[c] = captured_[c][i];
    for (int c = 0; c < 3; ++c) out[4 + c] = p.tex[c][i];
  }

  // uv (2 mul, 2 add), texel coordinates (2 mul, 3 add), fractions (2 add), four
  // texel reads, three bilinear blends of 3 lerps (9 mul, 18 add). Wrapping far
  // coordinates is integer masking in hardware (power-of-two sizes): not counted.
  static constexpr Ops kOpsPerPixel{/*add*/ 25, /*mul*/ 13, 0, 0, 0, 0, /*fetch*/ 4};
  static constexpr Ops kOpsPerSpan{/*add*/ 4, /*mul*/ 4};  // two plane seeds

 private:
  const core::Scene& scene_;
  Ops ops_;
  bool capture_ = false;
  float captured_[4][kSpanMax] = {};
};

}  // namespace modules
