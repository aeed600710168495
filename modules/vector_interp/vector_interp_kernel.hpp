#pragma once
// Interpolation of L and H (bump-mapping paper, Fig. 1: "interp L ─► normalize L",
// "interp H ─► normalize H"). L = light − P and V = eye − P are affine over a triangle
// in world space, so interpolating L/w and V/w on the screen and multiplying by w is
// exact; both are then normalized, and H = normalize(L̂ + V̂) is formed per pixel.
// Directional lights have a constant L, a viewer at infinity a constant V: when every
// light is directional and the viewer is at infinity, L and H are constant over the
// frame and this block is not elaborated at all (needed() is false).
#include <string>
#include <vector>

#include "modules/common/packet.hpp"

namespace modules {

class VectorInterpKernel {
 public:
  VectorInterpKernel(const core::Scene& scene, const std::vector<int>& point_lights);
  static bool needed(const core::Scene& scene);

  void process(SpanPacket& p);
  const Ops& ops() const { return ops_; }
  uint64_t work(const SpanPacket& p) const { return uint64_t(p.count); }  // pixels
  bool bypass(const SpanPacket&) const { return false; }

  Ops ops_per_pixel() const;
  Ops ops_per_span() const;

  // Waveforms: L and H of the first light whose H varies.
  void set_capture(bool) {}
  static std::vector<std::string> trace_names() { return {"l_x", "l_y", "l_z", "h_x", "h_y", "h_z"}; }
  void trace(const SpanPacket& p, int i, double* out) const;

 private:
  struct LightSlot {
    int light;  // index in the scene's lights, and in the packet's l and h
    int plane;  // slot of its L/w planes in TriangleSetup::l, or -1 (directional)
    float direction[3];  // unit L of a directional light
  };
  std::vector<LightSlot> lights_;
  bool local_viewer_;
  float view_[3];  // unit V of a viewer at infinity
  Ops ops_;
};

}  // namespace modules
