#pragma once
// Texel projection and weighting (object-space texturing paper): texture-object
// materials are textured in object space and filtered in the screen plane. Per
// triangle:
//
//   N = normalize((B − A) × (C − A)),  d = √(Ny² + Nz²)
//   cos α = Nz/d, sin α = Ny/d;  cos β = d, sin β = Nx   (1)–(2)  (d = 0: α = 0)
//   x' = x cos β − z cos α sin β − y sin α sin β,  y' = y cos α − z sin α            (6)
//   z' = x sin β + y Ny + z Nz, once per triangle                                   (7)
//
// — the rotation that lays the triangle parallel to the XY plane. One LOD per triangle
// (docs/object-space-texturing.md: the level whose texel spacing is at most one pixel
// on the most magnified part of the visible triangle). The texels of that level that
// cover the rotated triangle are visited; each is rotated back and projected with one
// matrix per triangle, M* = viewport · view-projection · [R]⁻¹, and splatted onto the
// four pixels around it with the area weights
//
//   S1 = (1 − fx)(1 − fy), S2 = fx·fy, S3 = fx(1 − fy), S4 = (1 − fx) fy
//
// (pixel centres at +½). A pixel accumulates Σ s·c and Σ s from the texels of the
// triangle visible there (the depth test: the framebuffer's visible triangle), and its
// texture colour is Σ s·c / Σ s. The lighting block left C = tex ⊙ D + S to be
// completed: this block composites it.
//
// The work runs after the frame's rasterization (the visibility it tests against must
// be final): a second pass. The texels are independent; the stats show how they divide
// across N parallel splat units.
//
// Under the DRAM model (docs/memory.md) its texel reads go through its cache, and each
// splat is a read-modify-write of the pixel's accumulator (Σ s·c and Σ s, four numbers
// of pipeline.texel_project.accumulator_bits) through a second cache of the same
// settings. The pass is timed as a whole: its cycles are the larger of its units' work
// and its DRAM bytes at the DRAM's rate, plus one latency.
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include <nlohmann/json.hpp>

#include "shadetlm/numeric/number.hpp"
#include "shadetlm/tlm/packet.hpp"
#include "shadetlm/modules/framebuffer/framebuffer_kernel.hpp"
#include "shadetlm/memory/cache.hpp"
#include "shadetlm/memory/dram.hpp"

namespace shadetlm::modules {

class Sampler;
struct MipMap;

// The rotation of (1)–(2) for a unit normal n: rows of R, so that R·n = +z.
struct PolygonRotation {
  double cos_a = 1, sin_a = 0, cos_b = 1, sin_b = 0;
  explicit PolygonRotation(const glm::dvec3& n);
  glm::dvec3 apply(const glm::dvec3& p, const glm::dvec3& n) const;   // (6), (7)
  glm::dvec3 inverse(const glm::dvec3& q, const glm::dvec3& n) const;  // Rᵀ·q
};

class TexelProjectKernel {
 public:
  // The projection of each texel and its splat weights run in `format`
  // (pipeline.texel_project.format).
  // memory: its caches' settings and the DRAM's timing (none: ideal memory);
  // accumulator_bits: of each of a pixel's four accumulated numbers.
  struct Memory {
    CacheConfig cache;
    DramTiming dram;
    int accumulator_bits = 32;
  };
  // The LOD rule (pipeline.texel_project.lod): the texel spacing on the screen at the
  // visible polygon's most magnified point (its clipped vertices), or the paper's rule:
  // the rotated polygon has one z', its distance from the eye, so one scale for all of
  // it, f / z' pixels per unit, as if it faced the viewer.
  enum class Lod { MostMagnified, ConstantZ };
  TexelProjectKernel(const core::Scene& scene, int units, core::NumberFormat format = {},
                     std::optional<Memory> memory = std::nullopt, Lod lod = Lod::MostMagnified);
  static bool needed(const core::Scene& scene);

  // The second pass over the frame in `fb`: splat, resolve, composite.
  void run(FramebufferKernel& fb);

  const Ops& ops() const { return ops_; }
  // Cycles of the pass at II 1: the busiest splat unit (units own interleaved 4×4 pixel
  // tiles; a texel goes to the owner of its first pixel, and its splats into neighbouring
  // tiles are writes across units, counted), then the resolve, spread likewise.
  // Under the DRAM model, at least its DRAM bytes at the DRAM's rate, plus a latency.
  uint64_t cycles() const { return cycles_; }
  // Its texel reads' cache (none: ideal memory); its accumulators' DRAM bytes.
  const MemoryClient* memory() const { return texel_memory_.get(); }
  uint64_t accumulator_bytes() const;
  nlohmann::json details() const;  // its figures in the statistics
  // Non-finite counts are of the texels' screen positions and w (dropped as off the
  // frame), in reduced formats only: in float32, w > 1e-6 keeps the position finite.
  NumberStats numbers() const {
    return {numbers_.format.name(), nonfinite_, numbers_.events, checks_outputs(numbers_.format, false)};
  }

  uint64_t polygons() const { return polygons_; }
  uint64_t lod_computations() const { return lod_computations_; }
  uint64_t texels() const { return texels_; }
  uint64_t splats() const { return splats_; }
  uint64_t covered() const { return covered_; }
  uint64_t holes() const { return holes_; }
  // Per texel: its four weights' sum minus 1, largest magnitude seen (should be ~1e-7).
  double weight_sum_error() const { return weight_sum_error_; }

  // Per row of the traversal: v, and the run of samples inside from the three edges
  // (per edge: its barycentric at u0, the bound: 3 mul, 3 add, 1 div), its ends.
  static constexpr Ops kOpsPerRow{/*add*/ 13, /*mul*/ 12, /*div*/ 3};
  // Per sample inside: its position in the rotated plane, a step along the row (2 add),
  // M* on it (6 mul, 6 add for clip x, y, w: A's clip position is the offset).
  static constexpr Ops kOpsProjection{/*add*/ 8, /*mul*/ 6};
  // Per texel on the frame: the perspective division (1 div, 2 mul), the viewport
  // (2 mul, 4 add), fractions (4 add), the four weights (4 mul, 4 add), its fetch; per
  // accepted pixel, Σ s·c and Σ s (3 mul, 4 add).
  static constexpr Ops kOpsPerTexel{/*add*/ 12, /*mul*/ 8, /*div*/ 1, 0, 0, 0, /*fetch*/ 1};
  static constexpr Ops kOpsPerAccumulation{/*add*/ 4, /*mul*/ 3};
  // Per covered pixel: the resolve (1 div, 3 mul) and the composite tex ⊙ D + S (3 mul, 3 add).
  static constexpr Ops kOpsPerPixel{/*add*/ 3, /*mul*/ 6, /*div*/ 1};

 private:
  // The splat pass, one triangle at a time, in the paper's steps (texel_project_kernel.cpp).
  struct Splat;
  void splat_triangle(const glm::dvec3 P[3], const glm::dvec2 uv[3], const core::Texture& texture,
                      const std::vector<const core::Texture*>& levels, uint32_t source, const FramebufferKernel& fb);
  void splat_constant(const Splat& s, const core::ClipPolygon& visible_part);
  void rotate_into_plane(const glm::dvec3 P[3], const glm::dvec3& n, const glm::dvec4& clip_a, Splat& s,
                         glm::dvec4& c_u, glm::dvec4& c_v);
  double most_magnified(const core::ClipPolygon& visible_part, const glm::dvec4& c_u, const glm::dvec4& c_v,
                        const Splat& s);
  double constant_z(const Splat& s);
  void choose_level(const core::ClipPolygon& visible_part, const std::vector<const core::Texture*>& levels,
                    const glm::dvec4& c_u, const glm::dvec4& c_v, Splat& s, glm::dvec2& uv_lo, glm::dvec2& uv_hi);
  void bound_samples(const glm::dvec2& uv_lo, const glm::dvec2& uv_hi, Splat& s);
  bool row_run(const Splat& s, long j, long& first, long& end, double& v, double& dv);
  template <class T> void splat_samples(Splat& s);
  // A sample on the frame: one call from the sample loop, which stays small for the many
  // samples it rejects (inlining it there cost the texturing benchmark 7 %); its steps
  // inlined into it (only texel_project_kernel.cpp calls them).
  template <class T>
  [[gnu::noinline]] void take_sample(Splat& s, long i, long j, double v, T x, T y, Sampler& bilinear,
                                     const MipMap& finest);
  [[gnu::always_inline]] inline void count_texel(Splat& s, long i, long j);
  [[gnu::always_inline]] inline void sample_colour(const Splat& s, long i, long j, double u, double v, Sampler& bilinear, const MipMap& finest,
                     float colour[3]);
  template <class T> [[gnu::always_inline]] inline void splat(const Splat& s, T x, T y, const float colour[3]);
  [[gnu::noinline]] void accumulate_in_memory(int px0, int py0, unsigned taken);

  const core::Scene& scene_;
  int units_;
  Lod lod_;
  glm::dmat4 view_projection_;
  std::vector<std::vector<core::Texture>> mips_;  // levels 1 … by texture index
  std::vector<double> accumulated_;              // Σ s·c (3 a pixel) and Σ s
  std::vector<uint64_t> unit_texels_, unit_round_robin_;
  Ops ops_;
  uint64_t polygons_ = 0, lod_computations_ = 0, texels_ = 0, splats_ = 0, covered_ = 0, holes_ = 0;
  uint64_t cycles_ = 0, oversampled_ = 0, budget_limited_ = 0, cross_unit_splats_ = 0;
  double weight_sum_error_ = 0;
  std::optional<Memory> memory_settings_;
  std::unique_ptr<MemoryClient> texel_memory_, accumulators_;  // none: ideal memory
  std::unordered_map<const core::Texture*, Surface> surfaces_;  // where each level lies
  Surface accumulator_surface_;
  NumberContext numbers_;
  uint64_t nonfinite_ = 0;
};

}  // namespace shadetlm::modules
