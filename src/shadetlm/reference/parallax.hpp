#pragma once
// The golden model's parallax: the exact first intersection of a view ray with the
// bilinearly interpolated height field, in double precision (docs/parallax.md). Its own
// code, independent of the pipeline's tracers and of core's exact cell test: it walks
// the cells the ray crosses and solves, per cell, the quadratic that the ray's height
// above the cell's bilinear patch is along the ray.
#include <glm/glm.hpp>

#include "shadetlm/core/texture.hpp"

namespace shadetlm::reference {

// The relief: height h(u, v) in [0, 1] (the map's first channel, clamped, bilinear with
// the map's wrap), the base polygon at h = 1, the deepest point h = 0, `depth` uv units
// below it. The ray enters at uv0 on the polygon and runs along d = (a, b, c) in uv units
// (c < 0: into the relief).
struct ParallaxHit {
  glm::dvec2 uv{0};     // where the ray first meets the relief
  double t = 0;         // the ray's parameter there (0: the entry)
  double t_exit = 0;    // where the ray leaves the first solid piece again (or the floor)
  double height = 1;    // the ray's height there, in [0, 1] (the relief's; 0 on the floor)
  bool traced = false;  // false: depth ≤ 0, or a ray parallel to the surface or leaving it
};
ParallaxHit parallax_hit(const core::Texture& height_map, glm::dvec2 uv0, glm::dvec3 d, double depth);

}  // namespace shadetlm::reference
