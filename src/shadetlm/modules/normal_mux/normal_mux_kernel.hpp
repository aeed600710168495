#pragma once
// The multiplexer of the bump-mapping paper's Fig. 3 — the one block the proposed
// hardware adds to the Phong hardware of Fig. 1: per packet it selects what goes on to
// the normalize block, the interpolated normal (phong, and bump-classic, whose
// perturbed normal replaces it) or the normal fetched from the texture of perturbed
// normals (bump-tangent, bump-square, bump-object). A select is wiring, not arithmetic:
// no operations are counted.
#include <string>
#include <vector>

#include "shadetlm/tlm/kernel_parts.hpp"
#include "shadetlm/tlm/packet.hpp"

namespace shadetlm::modules {

class NormalMuxKernel {
 public:
  static constexpr unsigned optional = Optional::none;  // (tlm/kernel_parts.hpp)
  static bool needed(const core::Scene& scene);

  // Packets whose normal is the interpolated one take the mux's other input: modelled as
  // the bypass wire (no cycles); the fetched normal is selected for the others.
  void process(SpanPacket& p) {
    for (int c = 0; c < 3; ++c)
      for (int i = 0; i < p.count; ++i) p.n[c][i] = p.bump[c][i];
  }
  const Ops& ops() const { return ops_; }
  Work work(const SpanPacket&) const { return {nullptr, 1}; }  // a pixel a cycle
  bool bypass(const SpanPacket& p) const { return !core::fetches_normal(p.tri->material->path); }

  // Waveforms: which input is selected (1: the fetched normal), and the normal out.
  void set_capture(bool) {}
  static std::vector<std::string> trace_names() { return {"select_fetched:int", "n_x", "n_y", "n_z"}; }
  void trace(const SpanPacket& p, int i, double* out) const {
    out[0] = core::fetches_normal(p.tri->material->path) ? 1 : 0;
    for (int c = 0; c < 3; ++c) out[1 + c] = p.n[c][i];
  }

 private:
  Ops ops_;
};

}  // namespace shadetlm::modules

namespace shadetlm::modules {
inline bool NormalMuxKernel::needed(const core::Scene& scene) {
  for (const auto& o : scene.objects)
    if (core::fetches_normal(scene.materials[size_t(o.material)].path)) return true;
  return false;
}
}  // namespace shadetlm::modules
