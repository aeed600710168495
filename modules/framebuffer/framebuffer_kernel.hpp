#pragma once
// The framebuffer: colour, coverage, depth (w, the eye-space depth) and normal layers
// of the frame, laid out as the golden model's (docs/golden-model.md). Depth testing
// happened early, in the raster block; a later packet at the same pixel is nearer.
#include <string>
#include <vector>

#include "core/frame.hpp"
#include "modules/common/packet.hpp"

namespace modules {

class FramebufferKernel {
 public:
  explicit FramebufferKernel(const core::Scene& scene);

  void process(SpanPacket& p);
  const Ops& ops() const { return ops_; }
  uint64_t work(const SpanPacket& p) const { return uint64_t(p.count); }
  bool bypass(const SpanPacket&) const { return false; }
  // Waveforms: what is written.
  void set_capture(bool) {}
  static std::vector<std::string> trace_names() { return {"r", "g", "b", "z"}; }
  void trace(const SpanPacket& p, int i, double* out) const {
    for (int c = 0; c < 3; ++c) out[c] = p.rgb[c][i];
    out[3] = p.w[i];
  }

  core::Frame& frame() { return frame_; }

 private:
  core::Frame frame_;
  float* layer_[8];  // R, G, B, A, Z, N.X, N.Y, N.Z
  Ops ops_;           // stores only: no arithmetic
};

}  // namespace modules
