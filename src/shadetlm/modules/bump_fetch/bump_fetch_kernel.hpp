#pragma once
// The bump fetch (bump-mapping paper, Fig. 3 "texture fetch N'_ts"; Fig. 2 "fetch Fu,
// Fv"): per pixel, perspective-correct uv and its screen derivatives, then the texture
// unit's filter (sampling/sampler.hpp) on the material's map:
//
//   bump-tangent, bump-square   the perturbed normal [a, b, c] in tangent space
//   bump-object                 the perturbed normal in object space
//   bump-classic                the height map's derivatives Fu, Fv
//
// Maps a scene names (normal_map) are used as stored; the others are computed when the
// pipeline is built, from the height map (core/bump_map.hpp) and, for the general
// tangent and object forms, from the object's surface — so one per object. Phong
// packets pass by untouched.
//
// Number formats: the filter is the texture unit's (float32, shared with texture_fetch);
// the value it hands on (N' or Fu, Fv) is rounded to the block's format. The normal
// maps' texels may be stored as a chip would, (N + 1) / 2 in 8, 10 or 16 bits
// (`stored`); the derivative map of bump-classic stays float.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "shadetlm/numeric/number.hpp"
#include "shadetlm/tlm/kernel_parts.hpp"
#include "shadetlm/tlm/packet.hpp"
#include "shadetlm/numeric/range.hpp"
#include "shadetlm/sampling/sampler.hpp"

namespace shadetlm::modules {

class BumpFetchKernel {
 public:
  static constexpr unsigned optional = Optional::ranges | Optional::numbers | Optional::memory | Optional::precompute;  // (tlm/kernel_parts.hpp)
  struct Options : FilterSetting {
    bool renormalize_mips = true;
    int stored_bits = 0;  // 0: float texels; 8, 10, 16: unsigned normalized, (N + 1) / 2
  };
  BumpFetchKernel(const core::Scene& scene, const Options& options, core::NumberFormat format = {});
  static bool needed(const core::Scene& scene);

  void process(SpanPacket& p) {
    fetch(p);
    if (numbers_.format.kind != core::NumberFormat::Kind::Float32)
      with_number_type(numbers_, [&](auto zero) {
        using T = decltype(zero);
        for (int c = 0; c < 3; ++c)
          for (int i = 0; i < p.count; ++i) p.bump[c][i] = float(T(p.bump[c][i]));
      });
    nonfinite_ += count_nonfinite(p.bump, p.count);
  }
  NumberStats numbers() const { return {numbers_.format.name(), nonfinite_, numbers_.events}; }
  const Ops& ops() const { return ops_; }
  // Four texels a cycle, at least one; the DRAM lines of each pixel under the DRAM model.
  Work work(const SpanPacket&) const { return {work_, 0, memory_ ? lines_ : nullptr}; }
  const MemoryClient* memory() const { return memory_.get(); }
  bool bypass(const SpanPacket& p) const { return !core::bump_path(p.tri->material->path); }

  double precompute_seconds() const { return precompute_s_; }
  Ranges ranges() const { return {{"uv", uv_range_}, {"fetched", fetched_range_}}; }

  // Waveforms: uv, the LOD and the filtered value.
  void set_capture(bool on) { capture_ = on; }
  static std::vector<std::string> trace_names() { return {"u", "v", "lod", "value_x", "value_y", "value_z"}; }
  void trace(const SpanPacket& p, int i, double* out) const {
    for (int c = 0; c < 3; ++c) out[c] = captured_[c][i];
    for (int c = 0; c < 3; ++c) out[3 + c] = p.bump[c][i];
  }

 private:
  struct Map {
    core::Texture base;
    std::vector<core::Texture> levels;
    MipMap mip;
  };
  const Map& build(const core::Scene& scene, const core::Object& object, const core::Material& m);

  const core::Scene& scene_;
  Options options_;
  NumberContext numbers_;
  Sampler sampler_;
  std::vector<std::unique_ptr<Map>> maps_;
  std::vector<const Map*> map_of_object_;  // by object index; nullptr: no bump map
  double precompute_s_ = 0;
  uint16_t work_[kSpanMax];
  std::unique_ptr<MemoryClient> memory_;  // none: ideal memory
  uint16_t lines_[kSpanMax] = {};
  Ops ops_;
  ValueRange uv_range_, fetched_range_;
  bool capture_ = false;
  float captured_[3][kSpanMax] = {};
  void fetch(SpanPacket& p);
  uint64_t nonfinite_ = 0;
};

}  // namespace shadetlm::modules
