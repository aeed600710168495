#pragma once
// The pipeline: the blocks of standard_pipeline(), in the order of the papers' figures,
//
//   main pass:   setup ─► raster ─► [parallax] ─► normal_interp ─► [bump_fetch] ─► [bump_perturb]
//                ─► [normal_mux] ─► normalize ─► [vector_interp] ─► [texture_fetch] ─► lighting
//                ─► framebuffer
//   splat pass:  [texel_project]
//
// (the blocks in brackets only where some material needs them: docs/pipeline.md), built
// for a scene (Pipeline) and run either as the SystemC/TLM-2.0 model (run_systemc) or as
// the same kernels in a plain C++ loop (run_loop): the two give bit-identical frames,
// which shows that the transaction-level wrapping changes nothing, and the loop is the
// speed baseline. Both engines, the settings and the statistics follow the declaration
// (tlm/block.hpp), to which a user may add blocks of their own.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "shadetlm/core/output.hpp"
#include "shadetlm/core/scene.hpp"
#include "shadetlm/tlm/block.hpp"
#include "shadetlm/stats/report.hpp"
#include "shadetlm/trace/trace.hpp"

namespace shadetlm::modules {

// The shading pipeline of the four papers: its settings and passes.
PipelineDecl standard_pipeline();

// The pipeline built for a scene: its settings resolved (bad ones throw
// core::InputError naming the scene file and setting) and the blocks some material
// needs (or every block: pipeline.elaborate = all), their kernels built — with the
// maps they precompute. The scene must outlive it.
class Pipeline {
 public:
  explicit Pipeline(const core::Scene& scene, const PipelineDecl& declaration = standard_pipeline());

  struct Elaborated {
    std::string name;
    Timing timing;
    std::unique_ptr<Block> block;
  };
  std::vector<Elaborated>& blocks() { return blocks_; }
  const core::Settings& settings() const { return settings_; }
  const PipelineSettings& pipeline_settings() const { return pipeline_; }
  // The DRAM's timing under pipeline.memory.model = dram (none: ideal memory).
  std::optional<DramTiming> dram() const { return pipeline_.dram_timing(); }
  const core::Scene& scene() const { return scene_; }
  double clock_mhz() const { return pipeline_.clock_mhz; }

 private:
  const core::Scene& scene_;
  core::Settings settings_;
  PipelineSettings pipeline_;
  std::vector<Elaborated> blocks_;
};

// What to record for inspection (docs/inspecting.md).
struct Inspect {
  std::string vcd;            // waveforms of `region` (and a .gtkw view beside them)
  TraceRegion region;         // pixels and triangles traced; also limits the timeline
  bool region_given = false;  // else the whole frame is traced
  std::string timeline;       // Chrome trace-event JSON
  std::string vectors;        // test vectors of the region: <folder>/<block>.{in,out}.hex (created)
  bool timing_log = false;    // keep every pixel's times at every block (RenderResult::timing_log)
  uint64_t bin_cycles = 0;      // utilization histogram bin (0: not kept; it costs a little per packet)
  std::function<void(double)> progress;  // share of the triangles set up, now and then (a progress bar)
  // The run's outputs, which the caller commits together with its own (the frame, the
  // statistics); null: the files above are committed when the simulation ends.
  core::OutputSet* outputs = nullptr;
};

// The blocks of `declaration` that write test vectors, and so the files --vectors
// writes in `folder` (trace/test_vectors.hpp).
std::vector<std::string> vector_files(const PipelineDecl& declaration, const std::string& folder);

RenderResult render_loop(const core::Scene& scene, const Inspect& inspect = {});
RenderResult render_loop(const core::Scene& scene, const PipelineDecl& declaration, const Inspect& inspect = {});
// Elaborates and simulates the SystemC pipeline: SystemC elaborates once per process,
// so call this at most once per process.
RenderResult render_systemc(const core::Scene& scene, const Inspect& inspect = {});
RenderResult render_systemc(const core::Scene& scene, const PipelineDecl& declaration, const Inspect& inspect = {});
// The same on a pipeline already built: the frame's work alone, without the maps the
// kernels precompute when they are built (RenderResult::precompute_s). scripts/bench.sh
// counts instructions inside these.
RenderResult run_loop(Pipeline& pipeline, const Inspect& inspect = {});
RenderResult run_systemc(Pipeline& pipeline, const Inspect& inspect = {});

// Writes a GTKWave save file for `vcd`: the blocks' signals grouped in pipeline
// order, real values drawn as analog steps.
// The view opens on the cycles [from, to] (the VCD's time unit is a cycle).
void write_gtkw(core::OutputSet& outputs, const std::string& path, const std::string& vcd, const std::vector<Tracer::ProbeInfo>& probes,
                uint64_t from, uint64_t to);

}  // namespace shadetlm::modules
