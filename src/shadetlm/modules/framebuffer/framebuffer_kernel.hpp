#pragma once
// The framebuffer: colour, coverage, depth (w, the eye-space depth) and normal layers
// of the frame, laid out as the golden model's (docs/golden-model.md), and the parallax
// tracer's iterations and traced hit (parallax.u, .v, .height) per pixel where a scene
// has a parallax material. Depth testing
// happened early, in the raster block; a later packet at the same pixel is nearer.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "shadetlm/core/frame.hpp"
#include "shadetlm/numeric/number.hpp"
#include "shadetlm/tlm/kernel_parts.hpp"
#include "shadetlm/tlm/packet.hpp"
#include "shadetlm/memory/cache.hpp"

namespace shadetlm::modules {

class FramebufferKernel {
 public:
  static constexpr unsigned optional = Optional::memory | Optional::end_pass;  // (tlm/kernel_parts.hpp)
  // deferred: keep, per pixel, the visible scene triangle and the specular term of
  // texture-object materials, for texel_project's second pass.
  // cache: the colour buffer's cache under the DRAM model (docs/memory.md; none: ideal
  // memory), RGBA in half floats (8 bytes a pixel), written back.
  explicit FramebufferKernel(const core::Scene& scene, bool deferred = false,
                             std::optional<CacheConfig> cache = std::nullopt);

  void process(SpanPacket& p);
  const Ops& ops() const { return ops_; }
  // A pixel a cycle; the DRAM lines of each pixel's colour write under the DRAM model.
  Work work(const SpanPacket&) const { return {nullptr, 1, memory_ ? lines_ : nullptr}; }
  const MemoryClient* memory() const { return memory_.get(); }
  static constexpr uint32_t kColourBytes = 8;
  bool bypass(const SpanPacket&) const { return false; }
  // Waveforms: what is written.
  void set_capture(bool) {}
  static std::vector<std::string> trace_names() { return {"r", "g", "b", "z"}; }
  void trace(const SpanPacket& p, int i, double* out) const {
    for (int c = 0; c < 3; ++c) out[c] = p.rgb[c][i];
    out[3] = p.w[i];
  }

  core::Frame& frame() { return frame_; }
  // The end of the pass: the frame goes on to the passes after it (texel_project's).
  void end_pass(PassEnd& e) { e.framebuffer = this; }
  // Colour, normal, depth and specular values that arrived NaN or infinite, replaced
  // before they reached the frame (in float32 none may arrive: the stress tests check it).
  uint64_t nonfinite() const { return nonfinite_; }
  // Deferred buffers (empty unless deferred): per pixel, 1 + the scene triangle of a
  // texture-object material seen there (0: none), and its specular term (3 floats).
  const std::vector<uint32_t>& visible_source() const { return visible_; }
  const std::vector<float>& specular() const { return specular_; }

 private:
  uint64_t nonfinite_ = 0;
  std::vector<uint32_t> visible_;
  std::vector<float> specular_;
  core::Frame frame_;
  float* layer_[8];  // R, G, B, A, Z, N.X, N.Y, N.Z
  float* iterations_ = nullptr;  // parallax.iterations, if the scene has a parallax material
  float* hit_[3] = {};           // parallax.u, .v, .height, likewise
  Ops ops_;           // stores only: no arithmetic
  std::unique_ptr<MemoryClient> memory_;  // none: ideal memory
  Surface colour_;
  uint16_t lines_[kSpanMax] = {};
  [[gnu::noinline]] void write_colour(const SpanPacket& p);  // through the cache (the DRAM model)
};

}  // namespace shadetlm::modules
