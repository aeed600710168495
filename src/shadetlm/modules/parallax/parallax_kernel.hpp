#pragma once
// The parallax block (parallax paper; docs/parallax.md): per pixel, the view ray in the
// relief's tangent space, traced into the height field; the corrected uv goes on to the
// colour fetch. Methods (material parallax.method):
//
//   offset    Welsh's parallax with offset limiting: one height fetch, T0 + depth·(1−h)·v̂xy
//   steep     layered linear search, a view-dependent layer count; stops at the first
//             layer under the relief
//   pom       steep, then the linear intersection of the last two layers
//   relief    steep, then a binary search between the last two layers
//   distance  sphere tracing on a distance map (parallax.map): the paper's refined map or
//             the box-gap map it refines — the same tracer, only the map differs — or
//             Donnelly's Euclidean map traced as published (s.steps trilinear steps)
//   cone      cone stepping on a safe cone map (parallax.cones): classic cones, free of
//             relief, or relaxed ones, which a step may end inside (then bisections on
//             the sign of z − D·h, before the exact cells)
//
// distance (refined, box-gap) and cone skip empty space, then walk the last cells with the exact per-cell
// test (core::march_cells) — the same finish for both, so that their iteration counts
// differ only by the skipping. Iterations: one per map or height read of the loop (a
// cell test counts one, with four texel fetches). Without early exit (parallax.early_exit
// = false) a pixel pays the loop's full length: every layer, or max_iterations.
//
// Under the DRAM model (docs/memory.md) its map reads go through its cache: the height
// field (4 bytes a texel), the distance map (4 bytes a voxel, slice after slice) or the
// cone map (8 bytes a cell: apex and ratio), each line once a pixel.
#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "shadetlm/core/parallax_map.hpp"
#include "shadetlm/numeric/number.hpp"
#include "shadetlm/tlm/kernel_parts.hpp"
#include "shadetlm/tlm/packet.hpp"
#include "shadetlm/memory/cache.hpp"
#include "shadetlm/tlm/settings.hpp"

namespace shadetlm::core {
class Settings;
}

namespace shadetlm::modules {

// The maps one material's tracer reads, built from its height map.
struct ParallaxMaps {
  core::HeightField field;
  core::VolumeMap volume;  // distance: refined, box-gap or Donnelly's
  core::ConeMap cone;      // cone
  int slices = 16;
  double precompute_s = 0;  // building the maps, or reading them
  bool loaded = false;      // read from the settings' map_file
};
// The key a map for these settings must carry (core::map_key): the map the method reads.
core::MapKey parallax_map_key(const core::HeightField& f, const core::ParallaxSettings& s);
// The maps the settings' method reads: read from s.map_file when it names one (checked
// against the key), else built.
ParallaxMaps build_parallax_maps(const core::Texture& height_map, const core::ParallaxSettings& s,
                                 const std::string& file);

struct ParallaxTrace {
  float x = 0, y = 0;  // where the ray meets the relief, in texels (tracer space)
  int iterations = 0;
  int fetches = 0;     // texels read
  int skips = 0;       // distance, cone: the iterations that skipped empty space (the rest tested cells)
  int cells = 0;       // of the iterations, the exact per-cell tests (distance, cone: the finish)
  int trilinear = 0;   // of the iterations, trilinear map reads (Donnelly's steps)
};
// The tracer's cycles for a trace: an iteration a cycle (a texture unit filters four
// texels a cycle: a bilinear height or one voxel), a trilinear read two, an exact cell
// test `cell_cycles`; at least one a pixel.
inline int64_t parallax_cycles(const ParallaxTrace& r, int64_t cell_cycles) {
  const int64_t plain = int64_t(r.iterations) - r.cells - r.trilinear;
  return std::max<int64_t>(1, plain + 2 * int64_t(r.trilinear) + int64_t(r.cells) * cell_cycles);
}
// The operations of one exact cell test, declared by hand: the test (core::march_cells,
// shared with the map builders) runs in float32 whatever the tracer's format, so a
// counting type does not see it (the tracer's operation check adds this a cell).
inline constexpr Ops kParallaxOpsCell{/*add*/ 16, /*mul*/ 18, /*div*/ 2, /*sqrt*/ 1, 0, 0, /*fetch*/ 4};
// The cycles of an exact cell test under the pipeline's settings: 18 mul, 2 div, a square
// root and four texels on one divider and one square-root unit (the divider twice).
int64_t parallax_cell_cycles(const PipelineSettings::Units& units);
// The tracer's map reads under the DRAM model: where one material's maps lie, and the
// lines a pixel touches (its line buffer), read through the cache at the pixel's end.
class MapReads {
 public:
  struct Place {
    Surface height, cone;
    std::vector<Surface> slices;  // the distance map's
  };
  explicit MapReads(MemoryClient& memory) : memory_(memory) {}
  // Places the maps of `m` (method: distance, cone or neither) one after another.
  Place place(const ParallaxMaps& m, bool distance, bool cone);
  void begin(const Place& place) { place_ = &place, lines_.clear(); }
  void bilinear(float x, float y);    // the four texels of core::bilinear_height
  void cell(int i, int j);            // the four corners of core::cell_hit's cell
  void voxel(float x, float y, float z, const core::VolumeMap& v);  // as VolumeMap::sample
  void trilinear(float x, float y, float z, const core::VolumeMap& v);  // as VolumeMap::trilinear
  void cone(int i, int j);            // a cone map cell (i, j within the map)
  uint16_t end();                     // the DRAM lines the pixel moved

 private:
  void texel(const Surface& s, int x, int y);  // wrapped
  MemoryClient& memory_;
  const Place* place_ = nullptr;
  LineBuffer lines_;
};

// Below this distance to the relief (voxels), skipping stops and the exact cells finish.
constexpr float kParallaxNear = 0.5f;

// Traces from texel position (x0, y0) on the base polygon along d = (a, b, c), the view
// direction in tangent space in uv units (a along Pu, b along Pv, c along the surface
// normal: c < 0 into the surface). A depth ≤ 0, or a ray with c ≥ 0 (parallel to the
// surface or leaving it), returns the entry point with 0 iterations. Adds the
// operations done to `ops` if given.
// `numbers`: the tracer's number format and event counters (nullptr: float32).
// `reads`: the map reads under the DRAM model (nullptr: ideal memory).
ParallaxTrace trace_parallax(const core::ParallaxSettings& s, const ParallaxMaps& m, float x0, float y0, float a,
                             float b, float c, Ops* ops = nullptr, NumberContext* numbers = nullptr,
                             MapReads* reads = nullptr);

class ParallaxKernel {
 public:
  static constexpr unsigned optional = Optional::numbers | Optional::details | Optional::memory | Optional::precompute;  // (tlm/kernel_parts.hpp)
  // The tracer runs in `format` (pipeline.parallax.format).
  // `cell_cycles`: the cycles of an exact cell test (one a step or read).
  // `cache`: its cache under the DRAM model (none: ideal memory).
  explicit ParallaxKernel(const core::Scene& scene, core::NumberFormat format = {}, int64_t cell_cycles = 1,
                          std::optional<CacheConfig> cache = std::nullopt);
  static bool needed(const core::Scene& scene);

  void process(SpanPacket& p);
  const Ops& ops() const { return ops_; }
  // parallax_cycles a pixel; the DRAM lines of each pixel's map reads.
  Work work(const SpanPacket&) const { return {work_, 0, memory_ ? lines_ : nullptr}; }
  const MemoryClient* memory() const { return memory_.get(); }
  bool bypass(const SpanPacket& p) const { return p.tri->material->path != core::ShadingPath::Parallax; }

  double precompute_seconds() const { return precompute_s_; }
  uint64_t iterations() const { return iterations_; }
  nlohmann::json details() const { return {{"iterations", iterations_}}; }
  NumberStats numbers() const { return {numbers_.format.name(), nonfinite_, numbers_.events}; }

  void set_capture(bool on) { capture_ = on; }
  static std::vector<std::string> trace_names() { return {"u", "v", "u_out", "v_out", "iterations:int"}; }
  void trace(const SpanPacket& p, int i, double* out) const {
    out[0] = captured_[0][i], out[1] = captured_[1][i];
    out[2] = p.uvp[0][i], out[3] = p.uvp[1][i], out[4] = p.iterations[i];
  }

 private:
  const core::Scene& scene_;
  std::vector<std::unique_ptr<ParallaxMaps>> maps_;  // by material index
  std::unique_ptr<MemoryClient> memory_;             // none: ideal memory
  std::unique_ptr<MapReads> reads_;
  std::vector<MapReads::Place> places_;               // by material index
  uint16_t lines_[kSpanMax] = {};
  uint64_t iterations_ = 0;
  uint16_t work_[kSpanMax];
  int64_t cell_cycles_ = 1;
  NumberContext numbers_;
  uint64_t nonfinite_ = 0;
  double precompute_s_ = 0;
  Ops ops_;
  bool capture_ = false;
  float captured_[2][kSpanMax] = {};  // u, v in, for the waveforms
};

}  // namespace shadetlm::modules
