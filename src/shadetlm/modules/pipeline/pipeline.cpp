#include "shadetlm/modules/pipeline/pipeline.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include <tlm_utils/tlm_quantumkeeper.h>

#include "shadetlm/core/input_error.hpp"
#include "shadetlm/core/output.hpp"

namespace shadetlm::modules {

// Each block's declaration, beside its kernel (modules/<name>/<name>_block.cpp).
BlockDecl setup_block(), raster_block(), parallax_block(), normal_interp_block(), bump_fetch_block(),
    bump_perturb_block(), normal_mux_block(), normalize_block(), vector_interp_block(), texture_fetch_block(),
    lighting_block(), framebuffer_block(), texel_project_block();

PipelineDecl standard_pipeline() {
  PipelineDecl d;
  d.settings = core::specs_of(PipelineSettings{});  // (tlm/settings.hpp)
  // The passes, in order. A pre-pass (a depth pre-pass, say) would go before "main".
  d.passes = {
      {"main",
       {setup_block(), raster_block(), parallax_block(), normal_interp_block(), bump_fetch_block(),
        bump_perturb_block(), normal_mux_block(), normalize_block(), vector_interp_block(), texture_fetch_block(),
        lighting_block(), framebuffer_block()}},
      {"splat", {texel_project_block()}},
  };
  return d;
}

namespace {
// The chain the engines run: a source, a raster, span blocks, then frame passes.
void check_shape(const std::vector<Pipeline::Elaborated>& blocks) {
  auto kind = [&](size_t i) { return blocks[i].block->kind(); };
  if (blocks.size() < 2 || kind(0) != Block::Kind::Source || kind(1) != Block::Kind::Raster)
    throw std::logic_error("a pipeline starts with a source block and a raster");
  for (size_t i = 2; i + 1 < blocks.size(); ++i)
    if (kind(i) == Block::Kind::Frame && kind(i + 1) != Block::Kind::Frame)
      throw std::logic_error("block " + blocks[i + 1].name + ": span blocks go before the frame passes");
}
}  // namespace

Pipeline::Pipeline(const core::Scene& scene, const PipelineDecl& declaration)
    : scene_(scene),
      settings_(scene.pipeline.resolve(declaration.all_settings())),
      pipeline_(core::read<PipelineSettings>(settings_, "")) {
  if (scene.lights.size() > size_t(kMaxLights))
    throw core::InputError(scene.file, "lights",
                           "the pipeline's lighting datapath holds at most " + std::to_string(kMaxLights) +
                               " lights, the scene has " + std::to_string(scene.lights.size()));
  // Only the blocks some material needs — or all of them (pipeline.elaborate = all), to
  // measure what the skipping saves.
  const bool all = pipeline_.elaborate == PipelineSettings::Elaborate::All;
  for (const auto& pass : declaration.passes)
    for (const auto& b : pass.blocks) {
      if (!all && b.needed && !b.needed(scene)) continue;
      const BlockBasics basics = core::read(settings_, b.name + ".", b.basics);
      const BlockContext ctx{scene, settings_, b.name, pipeline_, basics};
      Timing timing = basics.timing;
      if (basics.fifo == BlockBasics::Fifo::None) timing.fifo_depth = 0;
      if (basics.memory && basics.fifo != BlockBasics::Fifo::None && pipeline_.memory == PipelineSettings::Memory::Dram) {
        timing.line_bytes = basics.cache.line;
        timing.miss_queue = basics.miss_queue;
      }
      if (b.units) {
        const Timing units = b.units(ctx);
        timing.latency += units.latency;
        timing.ii = std::max(timing.ii, units.ii);
      }
      blocks_.push_back({b.name, timing, b.make(ctx)});
    }
  check_shape(blocks_);
}

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The SystemC top level: a module per elaborated block, each bound to the next.
class Top : public sc_core::sc_module {
 public:
  Top(sc_core::sc_module_name name, Pipeline& pipeline, const Inspect& inspect)
      : sc_core::sc_module(name), period_(1.0 / pipeline.clock_mhz(), sc_core::SC_US) {
    for (auto& b : pipeline.blocks()) modules_.push_back(b.block->module(b.name.c_str(), b.timing, period_));
    for (size_t i = 0; i + 1 < modules_.size(); ++i) {
      modules_[i]->bind_output(*modules_[i + 1]->input());
      if (pipeline.blocks()[i + 1].block->kind() == Block::Kind::Frame) modules_[i]->set_last_of_pass();
    }
    // The main pass's timing: the raster and the span blocks after it, in order.
    std::vector<Timing> line;
    for (size_t i = 1; i < modules_.size() && pipeline.blocks()[i].block->kind() != Block::Kind::Frame; ++i)
      line.push_back(pipeline.blocks()[i].timing);
    const DramTiming dram = pipeline.dram().value_or(DramTiming{});
    line_ = std::make_unique<MainPassTiming>(line, dram);
    if (inspect.timing_log) {
      log_ = std::make_unique<TimingLog>();
      line_->set_log(log_.get());
      for (size_t i = 0; i <= line.size(); ++i) log_->block(pipeline.blocks()[i].name, pipeline.blocks()[i].timing);
      if (line_->dram()) log_->memory(dram);
    }
    for (size_t i = 0; i <= line.size(); ++i) modules_[i]->join_line(line_.get(), int(i) - 1);
    // Over time, in bins of kept_bin cycles: the timeline's counters and the stats'
    // over_time are each regrouped from them, so neither's bins depend on the other's.
    kept_bin_ = kept_bin(inspect);
    // The DRAM's bytes over time: for the timeline's counter and the stats' over_time.
    if (line_->dram() && kept_bin_ > 0) line_->dram()->keep_histogram(kept_bin_);

    const core::Camera& camera = pipeline.scene().camera;
    region_ = inspect.region;
    if (!inspect.region_given) region_.x0 = 0, region_.y0 = 0, region_.x1 = camera.width - 1, region_.y1 = camera.height - 1;
    const TraceRegion* filter = inspect.region_given ? &region_ : nullptr;
    if (!inspect.vcd.empty()) tracer_ = std::make_unique<Tracer>(region_, period_);
    Timeline* timeline = inspect.timeline.empty() ? nullptr : &timeline_;
    if (timeline) timeline_.keep_fifos(uint32_t(modules_.size()), kTimelineBin);
    if (!inspect.vectors.empty())
      for (auto& m : modules_)
        if (auto layout = m->vector_layout()) {
          vectors_.push_back(std::make_unique<VectorFile>(m->block_name(), *layout));
          m->attach_vectors(vectors_.back().get());
        }
    for (size_t i = 0; i < modules_.size(); ++i) {
      const auto names = pipeline.blocks()[i].block->trace_names();
      const int probe = tracer_ && !names.empty() ? tracer_->add_probe(pipeline.blocks()[i].name, names) : -1;
      modules_[i]->attach(tracer_.get(), probe, timeline, uint32_t(i), filter);
      // Utilization over time: for the stats' over_time and the timeline's counters.
      modules_[i]->keep_histogram(kept_bin_);
      if (kTracing && (tracer_ || timeline) && i >= 1 && i <= line.size()) line_->watch(modules_[i].get());
    }
    // Waveforms of a region alone: the other packets need no times (the timeline's FIFO
    // counters need every packet's).
    if (tracer_ && !timeline && inspect.region_given)
      line_->watch_only([this](const SpanPacket& p) { return region_.covers(p.y, p.x0, p.x0 + p.count, p.tri->id); });
  }
  const MainPassTiming& line() const { return *line_; }
  TimingLog* log() const { return log_.get(); }
  const std::vector<std::unique_ptr<BlockInfo>>& modules() const { return modules_; }
  Tracer* tracer() { return tracer_.get(); }
  Timeline& timeline_slices() { return timeline_; }
  const std::vector<std::unique_ptr<VectorFile>>& vectors() const { return vectors_; }
  MainPassTiming& line() { return *line_; }
  // The timeline's utilization, DRAM and FIFO counters: a point every this many cycles,
  // with or without the stats' bins (a divisor of render --stats's 10 000).
  static constexpr uint64_t kTimelineBin = 250;
  // The bins kept while running: fine enough for the timeline's and the stats' (0: none).
  static uint64_t kept_bin(const Inspect& inspect) {
    const uint64_t timeline = inspect.timeline.empty() ? 0 : kTimelineBin;
    return std::gcd(timeline, inspect.bin_cycles);  // (gcd(0, b) = b)
  }
  uint64_t kept_bin() const { return kept_bin_; }
  std::vector<std::string> names() const {
    std::vector<std::string> n;
    for (const auto& m : modules_) n.push_back(m->block_name());
    return n;
  }

 private:
  sc_core::sc_time period_;
  std::vector<std::unique_ptr<BlockInfo>> modules_;
  TraceRegion region_;
  std::unique_ptr<Tracer> tracer_;
  std::vector<std::unique_ptr<VectorFile>> vectors_;
  Timeline timeline_;
  std::unique_ptr<MainPassTiming> line_;
  std::unique_ptr<TimingLog> log_;
  uint64_t kept_bin_ = 0;
};

}  // namespace

RenderResult render_loop(const core::Scene& scene, const Inspect& inspect) {
  return render_loop(scene, standard_pipeline(), inspect);
}
RenderResult render_loop(const core::Scene& scene, const PipelineDecl& declaration, const Inspect& inspect) {
  Pipeline pipeline(scene, declaration);
  return run_loop(pipeline, inspect);
}

RenderResult run_loop(Pipeline& pipeline, const Inspect& inspect) {
  auto& blocks = pipeline.blocks();
  if (inspect.progress) blocks[0].block->set_progress(inspect.progress);
  SpanChain chain;
  for (auto& b : blocks)
    if (b.block->kind() == Block::Kind::Span) chain.blocks.push_back(b.block.get());
  RenderResult r;
  r.engine = "loop";
  r.clock_mhz = pipeline.clock_mhz();
  r.dram = pipeline.dram();
  const auto start = std::chrono::steady_clock::now();
  blocks[0].block->run_pass(*blocks[1].block, chain);
  r.pixels_shaded = chain.pixels;
  PassEnd end;  // the main pass has ended: the passes after it run
  for (auto& b : blocks) b.block->end_pass(end);
  r.wall_s = seconds_since(start);
  for (auto& b : blocks) {
    BlockReport report;
    report.name = b.name;
    report.stats.ops = b.block->ops();
    report.timing = b.timing;
    b.block->finish(report, r);
    r.blocks.push_back(std::move(report));
  }
  return r;
}

RenderResult render_systemc(const core::Scene& scene, const Inspect& inspect) {
  return render_systemc(scene, standard_pipeline(), inspect);
}
RenderResult render_systemc(const core::Scene& scene, const PipelineDecl& declaration, const Inspect& inspect) {
  Pipeline pipeline(scene, declaration);
  return run_systemc(pipeline, inspect);
}

namespace {
// Bins of `from` cycles summed into bins of `to`, a multiple of `from`.
std::vector<uint64_t> regroup(const std::vector<uint64_t>& bins, uint64_t from, uint64_t to) {
  if (from == to || bins.empty()) return bins;
  const size_t k = size_t(to / from);
  std::vector<uint64_t> out((bins.size() + k - 1) / k, 0);
  for (size_t i = 0; i < bins.size(); ++i) out[i / k] += bins[i];
  return out;
}

// The timeline's counters from the run's bins (each block's busy cycles, the DRAM's
// bytes, the FIFOs' occupancy), then the file.
void write_timeline(core::OutputSet& outputs, Top& top, const RenderResult& r, const Inspect& inspect,
                    const std::string& scene) {
  Timeline& timeline = top.timeline_slices();
  const uint64_t bin = Top::kTimelineBin;
  for (const auto& m : top.modules())
    if (!m->times().busy_per_bin.empty())
      timeline.add_series(m->block_name() + " utilization", "percent", bin,
                          regroup(m->times().busy_per_bin, top.kept_bin(), bin), r.frame_cycles, 100);
  if (const Dram* dram = top.line().dram(); dram && !dram->bytes_per_bin().empty())
    timeline.add_series("DRAM bandwidth", "bytes_per_cycle", bin, regroup(dram->bytes_per_bin(), top.kept_bin(), bin),
                        r.frame_cycles, 1);
  std::vector<uint64_t> depths;
  for (const auto& m : top.modules()) depths.push_back(m->timing().fifo_depth);
  timeline.add_fifo_series(top.names(), depths, r.frame_cycles);
  if (inspect.region_given) timeline.limit_to_region();
  timeline.write(outputs, inspect.timeline, top.names(), r.clock_mhz, scene);
}
}  // namespace

constexpr uint64_t kFirstView = 256;  // cycles the waveform view opens on

namespace {
// The statistics the timing check holds the log's pixels against (the raster's walk, the
// pixels each span block worked), the frame passes' work and the frame's cycles.
void log_statistics(TimingLog& log, const RenderResult& r, const Top& top) {
  const size_t line = top.line().size();
  const Ops& ops = r.blocks[1].stats.ops;
  log.record("walked " + std::to_string(r.pixels_walked) + " " + std::to_string(r.pixels_hidden) + " " +
             std::to_string(ops.add) + " " + std::to_string(ops.mul) + " " + std::to_string(ops.div));
  for (size_t i = 2; i <= line; ++i)
    log.record("shaded " + r.blocks[i].name + " " + std::to_string(r.blocks[i].stats.pixels));
  for (size_t i = line + 1; i < top.modules().size(); ++i) {
    const BlockInfo& m = *top.modules()[i];
    const BlockInfo::PassWork w = m.pass_work();
    log.record("pass " + m.block_name() + " " + std::to_string(m.timing().latency) + " " +
               std::to_string(m.timing().ii) + " " + std::to_string(w.arrival) + " " + std::to_string(w.work) + " " +
               std::to_string(m.times().busy) + " " + std::to_string(m.times().last));
  }
  log.record("frame_end " + std::to_string(r.frame_cycles));
}
}  // namespace

RenderResult run_systemc(Pipeline& pipeline, const Inspect& inspect) {
  if (inspect.progress) pipeline.blocks()[0].block->set_progress(inspect.progress);
  const double clock_mhz = pipeline.clock_mhz();
  Top top("shadetlm", pipeline, inspect);
  // One quantum of 10 000 cycles: the source yields rarely, and never per pixel.
  tlm_utils::tlm_quantumkeeper::set_global_quantum(sc_core::sc_time(1e4 / clock_mhz, sc_core::SC_US));
  RenderResult r;
  r.engine = "systemc";
  r.clock_mhz = clock_mhz;
  r.dram = pipeline.dram();
  const auto start = std::chrono::steady_clock::now();
  sc_core::sc_start();
  r.wall_s = seconds_since(start);
  for (size_t i = 0; i < top.modules().size(); ++i) {
    const BlockInfo& m = *top.modules()[i];
    BlockReport report;
    report.name = m.block_name();
    report.stats = m.stats();
    report.timing = m.timing();
    report.last_cycle = m.times().last;
    if (inspect.bin_cycles > 0) report.busy_per_bin = regroup(m.times().busy_per_bin, top.kept_bin(), inspect.bin_cycles);
    r.frame_cycles = std::max(r.frame_cycles, uint64_t(report.last_cycle + 1));
    // Every packet the raster puts out reaches the end of the chain.
    if (pipeline.blocks()[i].block->kind() == Block::Kind::Raster) r.pixels_shaded = report.stats.pixels;
    pipeline.blocks()[i].block->finish(report, r);
    r.blocks.push_back(std::move(report));
  }
  r.frame_cycles = std::max(r.frame_cycles, uint64_t(top.line().end()));
  r.bin_cycles = inspect.bin_cycles;
  if (TimingLog* log = top.log()) {  // the main pass: setup and the line
    const auto& m = top.modules();
    log->end(std::max(top.line().end(), m[0]->times().last + 1));
    for (size_t i = 0; i <= top.line().size(); ++i) log->stats(m[i]->block_name(), m[i]->times());
    log_statistics(*log, r, top);
    r.timing_log = log->text();
  }
  core::OutputSet own;  // (when the caller has none)
  core::OutputSet& outputs = inspect.outputs ? *inspect.outputs : own;
  if (top.tracer()) {
    r.trace_records = top.tracer()->records();
    top.tracer()->write_vcd(outputs, inspect.vcd);
    // The view opens on the first traced packets: a window of kFirstView cycles, where a
    // one-cycle valid pulse is a few pixels wide.
    const uint64_t first = top.tracer()->first_cycle(), last = std::min(top.tracer()->last_cycle(), first + kFirstView);
    write_gtkw(outputs, inspect.vcd.substr(0, inspect.vcd.size() - 4) + ".gtkw", inspect.vcd, top.tracer()->probes(),
               first, last);
  }
  if (const Dram* dram = top.line().dram(); dram && inspect.bin_cycles > 0)
    r.dram_bytes_per_bin = regroup(dram->bytes_per_bin(), top.kept_bin(), inspect.bin_cycles);
  if (!inspect.timeline.empty()) write_timeline(outputs, top, r, inspect, pipeline.scene().file);
  for (const auto& v : top.vectors()) {
    for (bool in : {true, false}) outputs.write(vector_path(inspect.vectors, v->block(), in), v->text(in));
    r.vector_pixels += v->pixels();
  }
  if (!inspect.outputs) own.commit();
  return r;
}

std::vector<std::string> vector_files(const PipelineDecl& declaration, const std::string& folder) {
  std::vector<std::string> files;
  for (const auto& pass : declaration.passes)
    for (const auto& b : pass.blocks)
      if (b.vectors)
        for (bool in : {true, false}) files.push_back(vector_path(folder, b.name, in));
  return files;
}

void write_gtkw(core::OutputSet& outputs, const std::string& path, const std::string& vcd, const std::vector<Tracer::ProbeInfo>& probes,
                uint64_t from, uint64_t to) {
  // GTKWave's save format: "@<flags in hex>" sets how the following signals are
  // drawn, "-text" is a comment line. 28 = binary, right-justified (1-bit valid, ready);
  // 24 = decimal (x, y, triangle); 424 = signed decimal (integer values); 40020 = real,
  // its value written in the wave. The paths are relative, the VCD beside the view:
  // GTKWave finds the dump from where the view file is, so the pair can be moved.
  std::ostringstream out;
  {
    out << "[*] shadetlm: the blocks in pipeline order\n"
        << "[dumpfile] \"" << std::filesystem::path(vcd).filename().string() << "\"\n"
        << "[savefile] \"" << std::filesystem::path(path).filename().string() << "\"\n"
        << "[timestart] " << from << "\n[size] 1400 900\n[sst_width] 200\n[signals_width] 240\n"
        << "[sst_expanded] 1\n[treeopen] shadetlm.\n";
    // Zoom: GTKWave 3.3 shows about 4.3·2^-zoom time units (cycles here) across its
    // default wave pane (measured through its Tcl interface); show the window and 5 % more
    // (the dump runs 10 % past the traced span: a window past the dump's end resets the start).
    const double zoom = -std::log2(std::max(1.0, double(to - from) * 1.05 / 4.3));
    out << "*" << std::fixed << zoom << " -1\n";
    out << "@24\nshadetlm.cycle[63:0]\n";  // the time in cycles, first
    for (const auto& p : probes) {
      out << "@800200\n-" << p.block << "\n";  // a group per block
      for (size_t k = 0; k < p.names.size(); ++k) {
        if (k <= 1) out << "@28\n" << p.names[k] << "\n";  // valid, ready
        else if (k <= 4) out << "@24\n" << p.names[k] << "[31:0]\n";  // x, y, triangle
        else if (!p.is_real[k]) out << "@424\n" << p.names[k] << "[31:0]\n";
        else out << "@40020\n" << p.names[k] << "\n";
      }
      out << "@1000200\n-" << p.block << "\n";  // group end
    }
  }
  outputs.write(path, out.str());
}

}  // namespace shadetlm::modules
