#pragma once
// The texture unit's filter (docs/bump-mapping.md, "The texture unit"): a mip level per
// pixel from the screen-space derivatives of uv, then
//
//   nearest      the nearest texel of the nearest level
//   bilinear     four texels of the nearest level
//   trilinear    bilinear on the two levels around the LOD, blended
//   anisotropic  N trilinear probes spread along the footprint's major axis, averaged,
//                at the level of the footprint's width over N (not below its minor axis)
//
// with the addressing convention of core/texture.hpp (texel centres, wrap modes). It
// counts what the hardware spends: texel fetches, and the memory lines they touch —
// texels stored in 4×4 tiles, one 64-byte line per tile of 32-bit texels, counted once
// per pixel (a line buffer shared by a pixel's probes, no cache between pixels).
#include <cstdint>
#include <string>
#include <vector>

#include "core/texture.hpp"
#include "modules/common/ops.hpp"

namespace modules {

enum class Filter { Nearest, Bilinear, Trilinear, Anisotropic };
Filter parse_filter(const std::string& name);

// A texture and its mip levels, finest first.
struct MipMap {
  std::vector<const core::Texture*> levels;
};

class Sampler {
 public:
  Sampler(Filter filter, int probes) : filter_(filter), probes_(filter == Filter::Anisotropic ? probes : 1) {}

  // The filtered first three channels at (u, v); d*dx and d*dy are the derivatives of
  // u and v per pixel step right and down. Adds its operations to `ops`.
  void sample(const MipMap& map, float u, float v, float dudx, float dvdx, float dudy, float dvdy, float out[3],
              Ops& ops);

  // Bilinear probes per pixel at most: the texture unit's work in cycles at II 1.
  int probes_per_pixel() const { return filter_ == Filter::Trilinear ? 2 : filter_ == Filter::Anisotropic ? 2 * probes_ : 1; }
  Filter filter() const { return filter_; }

  // The LOD of the last sample (level, fraction included), for the waveforms.
  float last_lod() const { return lod_; }

 private:
  void bilinear(const core::Texture& t, int level, float u, float v, float out[3], Ops& ops);
  void nearest(const core::Texture& t, int level, float u, float v, float out[3], Ops& ops);
  void trilinear(const MipMap& map, float lod, float u, float v, float out[3], Ops& ops);
  void touch(int level, int x, int y);

  Filter filter_;
  int probes_;
  float lod_ = 0;
  uint64_t lines_[256];  // the lines touched by the current pixel
  int line_count_ = 0;
};

}  // namespace modules
