#pragma once
// The texture unit's filter (docs/bump-mapping.md, "The texture unit"): a mip level per
// pixel from the screen-space derivatives of uv, then
//
//   nearest      the nearest texel of the nearest level
//   bilinear     four texels of the nearest level
//   trilinear    bilinear on the two levels around the LOD, blended
//   anisotropic  N = ⌈major/minor⌉ trilinear probes (at most `probes`) spread along the
//                footprint's major axis, averaged, at the level of the footprint's
//                length over N (not below its minor axis)
//   ewa          Heckbert's elliptical weighted average: every texel inside the ellipse
//                inscribed in the pixel's footprint (eccentricity capped at 16), widened
//                by a unit reconstruction filter, on the level of its minor axis, weighted
//                by a Gaussian of its elliptical radius — the quality anchor
//
// with the addressing convention of core/texture.hpp (texel centres, wrap modes). It
// counts what the hardware spends: texel fetches, and the memory lines they touch —
// texels stored in 4×4 tiles, one 64-byte line per tile of 32-bit texels, counted once
// per pixel (a line buffer shared by a pixel's probes, no cache between pixels). Under
// the DRAM model (docs/memory.md) the lines are those of the unit's cache and layout,
// and each pixel's lines are read through its cache.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "shadetlm/core/texture.hpp"
#include "shadetlm/numeric/ops.hpp"
#include "shadetlm/tlm/packet.hpp"
#include "shadetlm/numeric/range.hpp"
#include "shadetlm/memory/cache.hpp"

namespace shadetlm::modules {

enum class Filter { Nearest, Bilinear, Trilinear, Anisotropic, Ewa };
// The filters' names (pipeline.<block>.filter), in the order of Filter.
const std::vector<std::string>& filter_names();  // in the order of Filter

// The filter a texture unit applies (pipeline.<block>.filter and .probes), and its
// cache under the DRAM model (none: ideal memory).
struct FilterSetting {
  Filter filter = Filter::Trilinear;
  int probes = 4;
  std::optional<CacheConfig> cache;
};

// A texture and its mip levels, finest first.
struct MipMap {
  std::vector<const core::Texture*> levels;
  std::vector<Surface> surfaces;  // where each level lies in the unit's memory (DRAM model)
};
// Places every level of `map` in `memory` (32-bit texels).
void place(MipMap& map, MemoryClient& memory);

class Sampler {
 public:
  Sampler(Filter filter, int probes) : filter_(filter), probes_(filter == Filter::Anisotropic ? probes : 1) {}
  // Reads each pixel's lines through `memory` (the DRAM model; the maps placed in it).
  void set_memory(MemoryClient* memory) { memory_ = memory; }
  MemoryClient* memory() const { return memory_; }

  // The filtered first three channels at (u, v); d*dx and d*dy are the derivatives of
  // u and v per pixel step right and down. Adds its operations to `ops`.
  void sample(const MipMap& map, float u, float v, float dudx, float dvdx, float dudy, float dvdy, float out[3],
              Ops& ops) {
    sample_as<float>(map, u, v, dudx, dvdx, dudy, dvdy, out, ops);
  }
  // The same on T: float, or Counted<float>, which counts what the code does (the
  // testbench holds the declared counts in `ops` to it).
  template <class T>
  void sample_as(const MipMap& map, T u, T v, T dudx, T dvdx, T dudy, T dvdy, T out[3], Ops& ops);

  // The texture unit's work so far, in cycles at II 1: it reads four texels a cycle, and
  // a pixel takes at least one cycle.
  uint64_t cycles() const { return cycles_; }
  Filter filter() const { return filter_; }

  // The LOD of the last sample (level, fraction included), for the waveforms.
  float last_lod() const { return lod_; }

 private:
  template <class T> void bilinear(const core::Texture& t, int level, T u, T v, T out[3], Ops& ops);
  template <class T> void nearest(const core::Texture& t, int level, T u, T v, T out[3], Ops& ops);
  template <class T> void trilinear(const MipMap& map, T lod, T u, T v, T out[3], Ops& ops);
  // du_major, dv_major: the derivatives along the footprint's major axis.
  template <class T>
  void anisotropic(const MipMap& map, T u, T v, T du_major, T dv_major, T major2, T minor2, T out[3], Ops& ops);
  template <class T> void ewa(const MipMap& map, T u, T v, T ax, T ay, T bx, T by, T out[3], Ops& ops);
  void touch(int level, int x, int y);
  [[gnu::noinline]] void touch_memory(int level, int x, int y);  // the line of the unit's layout (DRAM model)
  [[gnu::noinline]] void read_lines();  // the pixel's lines through the cache (DRAM model)

  Filter filter_;
  int probes_;
  float lod_ = 0;
  MemoryClient* memory_ = nullptr;
  const MipMap* map_ = nullptr;  // of the current sample
  LineBuffer lines_;  // the lines touched by the current pixel
  uint64_t cycles_ = 0;
};

// The texture unit on a span: per pixel, uv = (uv/w)·w from the triangle's uv planes,
// its derivatives along x and y, ((∂(u/w) − u ∂(1/w)) · w), and the filtered value into
// out[0..2][i]. `lod` (if not null) receives each pixel's LOD. Shared by the bump fetch
// and the colour texture's fetch.
// `cycles` receives each pixel's cycles in the texture unit, `lines` (if not null: the
// sampler has a memory) the DRAM lines it moved. T: float, or Counted<float> to count
// what the code does (the testbench's check of the declared counts).
template <class T = float>
void sample_span(const TriangleSetup& t, const SpanPacket& p, const MipMap& map, Sampler& sampler,
                 float out[3][kSpanMax], Ops& ops, ValueRange& uv_range, uint16_t cycles[kSpanMax],
                 float (*uv_lod)[kSpanMax] = nullptr, uint16_t* lines = nullptr);
// Per pixel outside the filter: uv (2 mul, 2 add) and its four derivatives (2 mul, 1 add
// each); per span, two plane seeds.
constexpr Ops kOpsSpanUvPerPixel{/*add*/ 6, /*mul*/ 10};
constexpr Ops kOpsSpanUvPerSpan{/*add*/ 4, /*mul*/ 4};

}  // namespace shadetlm::modules
