#pragma once
// The texture unit, for the material's colour texture: perspective-correct uv
// (uv/w interpolated, times w), then
//  * phong: a bilinear read of the finest level with the shared addressing convention
//    (core/texture.hpp: texel centres, wrap modes), as the golden model reads it;
//  * texture-screen: the screen-space filter of `texture_fetch.filter` on the texture's
//    mip chain (sampling/sampler.hpp; docs/object-space-texturing.md).
// Packets of materials without a texture, and of texture-object materials (whose colour
// texel_project splats), pass by untouched.
#include <string>
#include <vector>

#include "shadetlm/numeric/number.hpp"
#include "shadetlm/tlm/kernel_parts.hpp"
#include "shadetlm/tlm/packet.hpp"
#include "shadetlm/numeric/range.hpp"
#include "shadetlm/sampling/sampler.hpp"

namespace shadetlm::modules {

class TextureFetchKernel {
 public:
  static constexpr unsigned optional = Optional::numbers | Optional::details | Optional::memory;  // (tlm/kernel_parts.hpp)
  using Options = FilterSetting;
  TextureFetchKernel(const core::Scene& scene, const Options& options);
  static bool needed(const core::Scene& scene);

  void process(SpanPacket& p) {
    fetch(p);
    nonfinite_ += count_nonfinite(p.tex, p.count);
  }
  // float32 datapaths; the non-finite values among the block's outputs.
  NumberStats numbers() const { return {"float32", nonfinite_, {}}; }
  const Ops& ops() const { return ops_; }
  // Four texels a cycle, at least one; the DRAM lines of each pixel under the DRAM model.
  Work work(const SpanPacket&) const { return {work_, 0, memory_ ? lines_ : nullptr}; }
  const MemoryClient* memory() const { return memory_.get(); }
  bool bypass(const SpanPacket& p) const {
    return p.tri->material->texture < 0 || p.tri->material->path == core::ShadingPath::TextureObject;
  }
  uint64_t lod_computations() const { return lod_computations_; }
  nlohmann::json details() const { return {{"lod_computations", lod_computations_}}; }

  // Waveforms: uv, the texel address (x, y of the bilinear footprint's first texel)
  // and the filtered colour.
  void set_capture(bool on) { capture_ = on; }
  // texel_x, texel_y: the bilinear footprint's first texel (phong; −1 when filtered);
  // lod: the filter's level of detail (texture-screen; 0 for phong).
  static std::vector<std::string> trace_names() { return {"u", "v", "texel_x:int", "texel_y:int", "lod", "r", "g", "b"}; }
  void trace(const SpanPacket& p, int i, double* out) const {
    for (int c = 0; c < 5; ++c) out[c] = captured_[c][i];
    for (int c = 0; c < 3; ++c) out[5 + c] = p.tex[c][i];
  }

  // uv (2 mul, 2 add), texel coordinates (2 mul, 3 add), fractions (2 add), four
  // texel reads, three bilinear blends of 3 lerps (9 mul, 18 add). Wrapping far
  // coordinates is integer masking in hardware (power-of-two sizes): not counted.
  static constexpr Ops kOpsPerPixel{/*add*/ 25, /*mul*/ 13, 0, 0, 0, 0, /*fetch*/ 4};
  static constexpr Ops kOpsPerSpan{/*add*/ 4, /*mul*/ 4};  // two plane seeds

 private:
  void process_filtered(SpanPacket& p);  // texture-screen

  const core::Scene& scene_;
  Sampler sampler_;
  std::vector<std::vector<core::Texture>> levels_;  // mip levels 1 … by texture index (texture-screen)
  std::vector<MipMap> maps_;                        // by texture index
  uint64_t lod_computations_ = 0;
  uint16_t work_[kSpanMax];
  std::unique_ptr<MemoryClient> memory_;  // none: ideal memory
  std::vector<Surface> base_surfaces_;    // by texture index: the finest level (phong's bilinear read)
  uint16_t lines_[kSpanMax] = {};
  LineBuffer footprint_;  // the bilinear footprint's lines, each once
  void read_footprint(const Surface& s, int x0, int y0, int x1, int y1, int i);
  ValueRange uv_range_;
  Ops ops_;
  bool capture_ = false;
  float captured_[5][kSpanMax] = {};
  void fetch(SpanPacket& p);
  uint64_t nonfinite_ = 0;
};

}  // namespace shadetlm::modules
