#pragma once
// The pipeline: the blocks a scene needs, chained in the order of the papers' figures,
//
//   setup ─► raster ─► [parallax] ─► normal_interp ─► [bump_fetch] ─► [bump_perturb] ─► [normal_mux]
//         ─► normalize ─► [vector_interp] ─► [texture_fetch] ─► lighting ─► framebuffer
//
// (the blocks in brackets only where some material needs them: docs/pipeline.md)
//
// run either as the SystemC/TLM-2.0 model (render_systemc) or as the same kernels in a
// plain C++ loop (render_loop): the two give bit-identical frames, which shows that the
// transaction-level wrapping changes nothing, and the loop is the speed baseline.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/frame.hpp"
#include "core/scene.hpp"
#include "modules/bump_fetch/bump_fetch_kernel.hpp"
#include "modules/bump_perturb/bump_perturb_kernel.hpp"
#include "modules/common/block.hpp"
#include "modules/common/timeline.hpp"
#include "modules/common/trace.hpp"
#include "modules/framebuffer/framebuffer_kernel.hpp"
#include "modules/lighting/lighting_kernel.hpp"
#include "modules/normal_interp/normal_interp_kernel.hpp"
#include "modules/normal_mux/normal_mux_kernel.hpp"
#include "modules/normalize/normalize_kernel.hpp"
#include "modules/parallax/parallax_kernel.hpp"
#include "modules/raster/raster_kernel.hpp"
#include "modules/setup/setup_kernel.hpp"
#include "modules/texel_project/texel_project_kernel.hpp"
#include "modules/texture_fetch/texture_fetch_kernel.hpp"
#include "modules/vector_interp/vector_interp_kernel.hpp"

namespace modules {

// The blocks in pipeline order (the names of their folders, settings and statistics).
const std::vector<std::string>& block_names();

struct Options {
  bool perspective = true;
  int reseed = 0;  // normal_interp.reseed: 0 none, −1 per line, N every N pixels
  NormalizeMode normalize = NormalizeMode::Exact;
  double clock_mhz = 500;
  bool elaborate_all = false;  // pipeline.elaborate = all: every block, needed or not
  BumpFetchKernel::Options bump;
  TextureFetchKernel::Options texture;
  int splat_units = 4;  // texel_project.units
  bool affine_bump_vectors = false;  // vector_interp.bump_vectors
  std::map<std::string, core::NumberFormat> formats;  // <block>.format, by block (core::formatted_blocks)
  std::map<std::string, Timing> timing;  // by block name
};
// Reads the scene's pipeline section; throws core::InputError for what the pipeline
// cannot model (more than kMaxLights lights).
Options read_options(const core::Scene& scene);

// The kernels of one frame, created for what the scene needs.
struct Kernels {
  Kernels(const core::Scene& scene, const Options& options);
  SetupKernel setup;
  RasterKernel raster;
  std::optional<ParallaxKernel> parallax;         // only if a material has the parallax path
  NormalInterpKernel normal_interp;
  std::optional<BumpFetchKernel> bump_fetch;      // only if a material has a bump path
  std::optional<BumpPerturbKernel> bump_perturb;  // only for bump-classic
  std::optional<NormalMuxKernel> normal_mux;      // only for the fetched-normal bump paths
  NormalizeKernel normalize;
  std::optional<VectorInterpKernel> vector_interp;  // only for point lights or a local viewer
  std::optional<TextureFetchKernel> texture_fetch;  // only if a material has a texture
  LightingKernel lighting;
  FramebufferKernel framebuffer;
  std::optional<TexelProjectKernel> texel_project;  // only for texture-object materials
};

struct BlockReport {
  std::string name;
  BlockStats stats;
  Timing timing;
  uint64_t free_cycle = 0;  // when it finished its last work
  std::vector<uint64_t> busy_per_bin;  // busy cycles per Inspect::bin_cycles
  Ranges ranges;                       // of the block's datapaths (docs/pipeline.md)
  nlohmann::json details;              // block-specific figures (texel_project)
  std::optional<NumberStats> numbers;  // its number format and what its numbers met
};

// What to record for inspection (docs/inspecting.md).
struct Inspect {
  std::string vcd;            // waveforms of `region` (and a .gtkw view beside them)
  TraceRegion region;         // pixels and triangles traced; also limits the timeline
  bool region_given = false;  // else the whole frame is traced
  std::string timeline;       // Chrome trace-event JSON
  uint64_t bin_cycles = 0;      // utilization histogram bin (0: not kept; it costs a little per packet)
  std::function<void(double)> progress;  // share of the triangles set up, now and then (a progress bar)
};

struct RenderResult {
  core::Frame frame;
  std::string engine;  // "systemc" or "loop"
  double wall_s = 0;
  double clock_mhz = 0;
  uint64_t frame_cycles = 0;  // 0 for the loop, which has no timing model
  uint64_t triangles_in = 0, triangles_drawn = 0;
  uint64_t pixels_walked = 0, pixels_hidden = 0, pixels_shaded = 0;
  std::vector<BlockReport> blocks;  // elaborated blocks, in pipeline order
  uint64_t bin_cycles = 0;          // of the blocks' busy_per_bin (0: none)
  uint64_t trace_records = 0;       // pixels written to the VCD, all blocks
  double precompute_s = 0;          // bump maps built when the pipeline was (not in wall_s)
  uint64_t nonfinite_replaced = 0;   // NaN or infinite colour, normal, depth or specular values that reached the framebuffer (replaced)

  const BlockReport* bottleneck() const;  // the block with the most busy cycles
  Ops total_ops() const;
  nlohmann::json stats_json() const;
};

RenderResult render_loop(const core::Scene& scene, const Inspect& inspect = {});
// Elaborates and simulates the SystemC pipeline: SystemC elaborates once per process,
// so call this at most once per process.
RenderResult render_systemc(const core::Scene& scene, const Inspect& inspect = {});
// The same on kernels already built: the frame's work alone, without the maps the
// kernels precompute when they are built (RenderResult::precompute_s). scripts/bench.sh
// counts instructions inside these.
RenderResult run_loop(Kernels& kernels, const Options& options, const Inspect& inspect = {});
RenderResult run_systemc(Kernels& kernels, const Options& options, const Inspect& inspect = {});

// Writes a GTKWave save file for `vcd`: the blocks' signals grouped in pipeline
// order, real values drawn as analog steps.
// The view opens on [from_ps, to_ps].
void write_gtkw(const std::string& path, const std::string& vcd, const std::vector<Tracer::ProbeInfo>& probes,
                double from_ps, double to_ps);

}  // namespace modules
