#pragma once
// Interpolation of L and H (bump-mapping paper, Fig. 1: "interp L ─► normalize L",
// "interp H ─► normalize H"). L = light − P and V = eye − P are affine over a triangle
// in world space, so interpolating L/w and V/w on the screen and multiplying by w is
// exact; both are then normalized, and H = normalize(L̂ + V̂) is formed per pixel.
// Directional lights have a constant L, a viewer at infinity a constant V: when every
// light is directional and the viewer is at infinity, L and H are constant over the
// frame and this block does nothing for Phong packets (it is not elaborated at all
// unless a bump material needs it).
//
// Fetched-normal bump paths (bump-mapping paper, Fig. 3) light in the texture's space:
// L and H of every light, transformed into tangent (or object) space at the vertices
// by setup, are interpolated here and normalized per pixel — the paper's vertex-only
// transformation, whose error docs/bump-mapping.md measures.
#include <string>
#include <vector>

#include "shadetlm/numeric/number.hpp"
#include "shadetlm/tlm/kernel_parts.hpp"
#include "shadetlm/tlm/packet.hpp"
#include "shadetlm/numeric/range.hpp"

namespace shadetlm::modules {

class VectorInterpKernel {
 public:
  static constexpr unsigned optional = Optional::ranges | Optional::numbers;  // (tlm/kernel_parts.hpp)
  // Its datapaths are of `format` (pipeline.vector_interp.format).
  VectorInterpKernel(const core::Scene& scene, const std::vector<int>& point_lights, bool affine_bump_vectors = false,
                     core::NumberFormat format = {}, bool interpolate_h = false);
  // World-space L or H vary over the frame (point lights, a local viewer).
  static bool needed_in_world(const core::Scene& scene);
  static bool needed(const core::Scene& scene);

  void process(SpanPacket& p);
  Ops ops() const;
  Work work(const SpanPacket&) const { return {nullptr, 1}; }  // a pixel a cycle
  bool bypass(const SpanPacket& p) const { return !world_ && !core::fetches_normal(p.tri->material->path); }
  Ranges ranges() const { return {{"l", l_range_}, {"h", h_range_}}; }
  NumberStats numbers() const { return {numbers_.format.name(), nonfinite_, numbers_.events}; }

  Ops ops_per_pixel() const;
  Ops ops_per_span() const;
  Ops ops_per_pixel_in_space() const;  // fetched-normal paths

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
  template <class T> void process_in_space(SpanPacket& p);
  template <class T> void process_in_world(SpanPacket& p);

  std::vector<LightSlot> lights_;
  int light_count_;  // all the scene's lights
  bool world_;       // needed_in_world()
  bool affine_bump_vectors_;
  bool interpolate_h_;  // world paths: H from setup's planes (Fig. 1), not from L̂ + V̂
  bool local_viewer_;
  ValueRange l_range_, h_range_;  // interpolated, before normalization
  float view_[3];  // unit V of a viewer at infinity
  PacketTally<2> tally_;  // packets in the world (0) and in the texture's space (1)
  NumberContext numbers_;
  uint64_t nonfinite_ = 0;
  bool writes_l_[kMaxLights] = {}, writes_h_[kMaxLights] = {};  // in the world: the lights' L and H it writes
};

}  // namespace shadetlm::modules
