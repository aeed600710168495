#include "modules/pipeline/pipeline.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>

#include "core/input_error.hpp"
#include "modules/raster/raster.hpp"
#include "modules/setup/setup.hpp"
#include "modules/texel_project/texel_project.hpp"

namespace modules {

const std::vector<std::string>& block_names() {
  static const std::vector<std::string> names = {
      "setup",     "raster",        "parallax",      "normal_interp", "bump_fetch", "bump_perturb", "normal_mux",
      "normalize", "vector_interp", "texture_fetch", "lighting",   "framebuffer", "texel_project"};
  return names;
}

Options read_options(const core::Scene& scene) {
  if (scene.lights.size() > size_t(kMaxLights))
    throw core::InputError(scene.file, "lights",
                           "the pipeline's lighting datapath holds at most " + std::to_string(kMaxLights) +
                               " lights, the scene has " + std::to_string(scene.lights.size()));
  Options o;
  o.perspective = scene.pipeline.string("normal_interp.mode") == "perspective";
  const std::string reseed = scene.pipeline.string("normal_interp.reseed");
  o.reseed = reseed == "none" ? 0 : reseed == "line" ? -1 : std::stoi(reseed.substr(4));  // tileN
  o.normalize = parse_normalize_mode(scene.pipeline.string("normalize.mode"));
  o.clock_mhz = scene.pipeline.number("clock_mhz");
  o.elaborate_all = scene.pipeline.string("elaborate") == "all";
  o.affine_bump_vectors = scene.pipeline.string("vector_interp.bump_vectors") == "affine";
  o.texture.filter = parse_filter(scene.pipeline.string("texture_fetch.filter"));
  o.texture.probes = scene.pipeline.integer("texture_fetch.probes");
  o.splat_units = scene.pipeline.integer("texel_project.units");
  o.bump.filter = parse_filter(scene.pipeline.string("bump_fetch.filter"));
  o.bump.probes = scene.pipeline.integer("bump_fetch.probes");
  o.bump.renormalize_mips = scene.pipeline.boolean("bump_fetch.renormalize_mips");
  for (const auto& b : core::formatted_blocks()) o.formats[b] = scene.pipeline.format(b);
  for (const auto& b : block_names())
    o.timing[b] = Timing{uint64_t(scene.pipeline.integer(b + ".latency")),
                         uint64_t(scene.pipeline.integer(b + ".ii"))};
  return o;
}

Kernels::Kernels(const core::Scene& scene, const Options& o)
    : setup(scene, o.perspective, o.affine_bump_vectors),
      raster(scene.camera.width, scene.camera.height),
      normal_interp(o.reseed, o.formats.at("normal_interp")),
      normalize(o.normalize, o.formats.at("normalize")),
      lighting(scene, o.formats.at("lighting")),
      framebuffer(scene, TexelProjectKernel::needed(scene)) {
  // Only the blocks some material needs — or all of them (pipeline.elaborate = all), to
  // measure what the skipping saves.
  const bool all = o.elaborate_all;
  if (all || TexelProjectKernel::needed(scene)) texel_project.emplace(scene, o.splat_units, o.formats.at("texel_project"));
  if (all || ParallaxKernel::needed(scene)) parallax.emplace(scene, o.formats.at("parallax"));
  if (all || BumpFetchKernel::needed(scene)) bump_fetch.emplace(scene, o.bump);
  if (all || BumpPerturbKernel::needed(scene)) bump_perturb.emplace(o.perspective);
  if (all || NormalMuxKernel::needed(scene)) normal_mux.emplace();
  if (all || VectorInterpKernel::needed(scene))
    vector_interp.emplace(scene, setup.point_lights(), o.affine_bump_vectors, o.formats.at("vector_interp"));
  if (all || TextureFetchKernel::needed(scene)) texture_fetch.emplace(scene, o.texture);
}

namespace {

void fill_counts(RenderResult& r, const Kernels& k) {
  r.triangles_in = k.setup.triangles_in();
  r.triangles_drawn = k.setup.triangles_out();
  r.pixels_walked = k.raster.pixels_walked();
  r.pixels_hidden = k.raster.pixels_hidden();
  r.precompute_s = (k.bump_fetch ? k.bump_fetch->precompute_seconds() : 0.0) +
                   (k.parallax ? k.parallax->precompute_seconds() : 0.0);
  r.nonfinite_replaced = k.framebuffer.nonfinite();
  for (auto& b : r.blocks) {
    if (b.name == "normal_interp") b.ranges = k.normal_interp.ranges(), b.numbers = k.normal_interp.numbers();
    if (b.name == "normalize") b.numbers = k.normalize.numbers();
    if (b.name == "lighting") b.numbers = k.lighting.numbers();
    if (b.name == "vector_interp") b.numbers = k.vector_interp->numbers();
    if (b.name == "bump_fetch") b.ranges = k.bump_fetch->ranges(), b.numbers = k.bump_fetch->numbers();
    if (b.name == "bump_perturb") b.ranges = k.bump_perturb->ranges(), b.numbers = k.bump_perturb->numbers();
    if (b.name == "texture_fetch") b.numbers = k.texture_fetch->numbers();
    if (b.name == "vector_interp") b.ranges = k.vector_interp->ranges();
    if (b.name == "texel_project") b.details = k.texel_project->stats(), b.numbers = k.texel_project->numbers();
    if (b.name == "texture_fetch") b.details = {{"lod_computations", k.texture_fetch->lod_computations()}};
    if (b.name == "parallax") b.details = {{"iterations", k.parallax->iterations()}}, b.numbers = k.parallax->numbers();
  }
}


double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The SystemC top level: the blocks the scene needs, bound in a chain.
class Top : public sc_core::sc_module {
 public:
  Top(sc_core::sc_module_name name, Kernels& k, const Options& o, const Inspect& inspect, int width, int height)
      : sc_core::sc_module(name), period_(1.0 / o.clock_mhz, sc_core::SC_US) {
    setup_ = std::make_unique<Setup>("setup", k.setup, o.timing.at("setup"), period_);
    raster_ = std::make_unique<Raster>("raster", k.raster, o.timing.at("raster"), period_);
    setup_->out.bind(raster_->in);
    blocks_ = {setup_.get(), raster_.get()};
    // Binds the output of the last block so far to the next one's input.
    std::function<void(tlm::tlm_target_socket<32>&)> bind_last = [&](auto& in) { raster_->out.bind(in); };
    auto add = [&](auto stage) {
      bind_last(stage->in);
      bind_last = [s = stage.get()](auto& in) { s->out.bind(in); };
      blocks_.push_back(stage.get());
      return stage;
    };
    if (k.parallax) parallax_ = add(stage("parallax", *k.parallax, o));
    normal_interp_ = add(stage("normal_interp", k.normal_interp, o));
    if (k.bump_fetch) bump_fetch_ = add(stage("bump_fetch", *k.bump_fetch, o));
    if (k.bump_perturb) bump_perturb_ = add(stage("bump_perturb", *k.bump_perturb, o));
    if (k.normal_mux) normal_mux_ = add(stage("normal_mux", *k.normal_mux, o));
    normalize_ = add(stage("normalize", k.normalize, o));
    if (k.vector_interp) vector_interp_ = add(stage("vector_interp", *k.vector_interp, o));
    if (k.texture_fetch) texture_fetch_ = add(stage("texture_fetch", *k.texture_fetch, o));
    lighting_ = add(stage("lighting", k.lighting, o));
    // The framebuffer ends the chain: its output socket stays unbound.
    framebuffer_ = stage("framebuffer", k.framebuffer, o);
    bind_last(framebuffer_->in);
    blocks_.push_back(framebuffer_.get());
    if (k.texel_project) {
      texel_project_ = std::make_unique<TexelProject>("texel_project", *k.texel_project, k.framebuffer, *setup_,
                                                      *framebuffer_, o.timing.at("texel_project"), period_);
      blocks_.push_back(texel_project_.get());
    }

    region_ = inspect.region;
    if (!inspect.region_given) region_.x0 = 0, region_.y0 = 0, region_.x1 = width - 1, region_.y1 = height - 1;
    filter_ = inspect.region_given ? &region_ : nullptr;
    if (!inspect.vcd.empty()) tracer_ = std::make_unique<Tracer>("tracer", inspect.vcd, region_, period_);
    auto probe = [&](const std::string& name, const std::vector<std::string>& values) {
      return tracer_ ? tracer_->add_probe(name, values) : -1;
    };
    setup_->attach(tracer_.get(), -1, timeline(inspect), 0, filter_);
    raster_->attach(tracer_.get(), probe("raster", Raster::trace_names()), timeline(inspect), 1, filter_);
    attach(parallax_.get(), probe, inspect);
    attach(normal_interp_.get(), probe, inspect);
    attach(bump_fetch_.get(), probe, inspect);
    attach(bump_perturb_.get(), probe, inspect);
    attach(normal_mux_.get(), probe, inspect);
    attach(normalize_.get(), probe, inspect);
    attach(vector_interp_.get(), probe, inspect);
    attach(texture_fetch_.get(), probe, inspect);
    attach(lighting_.get(), probe, inspect);
    attach(framebuffer_.get(), probe, inspect);
    for (BlockInfo* b : blocks_) b->schedule().keep_histogram(inspect.bin_cycles);
  }
  const std::vector<BlockInfo*>& blocks() const { return blocks_; }
  const Tracer* tracer() const { return tracer_.get(); }
  const Timeline& timeline_slices() const { return timeline_; }
  std::vector<std::string> names() const {
    std::vector<std::string> n;
    for (BlockInfo* b : blocks_) n.push_back(b->block_name());
    return n;
  }

 private:
  Timeline* timeline(const Inspect& inspect) { return inspect.timeline.empty() ? nullptr : &timeline_; }
  template <class K, class Probe>
  void attach(Stage<K>* s, Probe& probe, const Inspect& inspect) {
    if (!s) return;
    const auto track = uint32_t(std::find(blocks_.begin(), blocks_.end(), s) - blocks_.begin());
    s->attach(tracer_.get(), probe(s->block_name(), K::trace_names()), timeline(inspect), track, filter_);
  }
  template <class K>
  std::unique_ptr<Stage<K>> stage(const char* name, K& kernel, const Options& o) {
    return std::make_unique<Stage<K>>(name, kernel, o.timing.at(name), period_);
  }

  sc_core::sc_time period_;
  std::unique_ptr<Setup> setup_;
  std::unique_ptr<Raster> raster_;
  std::unique_ptr<Stage<ParallaxKernel>> parallax_;
  std::unique_ptr<Stage<NormalInterpKernel>> normal_interp_;
  std::unique_ptr<Stage<BumpFetchKernel>> bump_fetch_;
  std::unique_ptr<Stage<BumpPerturbKernel>> bump_perturb_;
  std::unique_ptr<Stage<NormalMuxKernel>> normal_mux_;
  std::unique_ptr<Stage<NormalizeKernel>> normalize_;
  std::unique_ptr<Stage<VectorInterpKernel>> vector_interp_;
  std::unique_ptr<Stage<TextureFetchKernel>> texture_fetch_;
  std::unique_ptr<Stage<LightingKernel>> lighting_;
  std::unique_ptr<Stage<FramebufferKernel>> framebuffer_;
  std::unique_ptr<TexelProject> texel_project_;
  std::vector<BlockInfo*> blocks_;
  TraceRegion region_;
  const TraceRegion* filter_ = nullptr;
  std::unique_ptr<Tracer> tracer_;
  Timeline timeline_;
};

}  // namespace

RenderResult render_loop(const core::Scene& scene, const Inspect& inspect) {
  const Options o = read_options(scene);
  Kernels k(scene, o);
  return run_loop(k, o, inspect);
}

RenderResult run_loop(Kernels& k, const Options& o, const Inspect& inspect) {
  if (inspect.progress) k.setup.set_progress(inspect.progress);
  RenderResult r;
  r.engine = "loop";
  r.clock_mhz = o.clock_mhz;
  const auto start = std::chrono::steady_clock::now();
  k.setup.run([&](const TriangleSetup& t) {
    k.raster.run(t, [&](SpanPacket& p) {
      if (k.parallax && !k.parallax->bypass(p)) k.parallax->process(p);
      if (!k.normal_interp.bypass(p)) k.normal_interp.process(p);
      if (k.bump_fetch && !k.bump_fetch->bypass(p)) k.bump_fetch->process(p);
      if (k.bump_perturb && !k.bump_perturb->bypass(p)) k.bump_perturb->process(p);
      if (k.normal_mux && !k.normal_mux->bypass(p)) k.normal_mux->process(p);
      k.normalize.process(p);
      if (k.vector_interp && !k.vector_interp->bypass(p)) k.vector_interp->process(p);
      if (k.texture_fetch && !k.texture_fetch->bypass(p)) k.texture_fetch->process(p);
      k.lighting.process(p);
      k.framebuffer.process(p);
      r.pixels_shaded += uint64_t(p.count);
    });
  });
  if (k.texel_project) k.texel_project->run(k.framebuffer);
  r.wall_s = seconds_since(start);
  auto report = [&](const char* name, const Ops& ops) {
    BlockReport b;
    b.name = name;
    b.stats.ops = ops;
    b.timing = o.timing.at(name);
    r.blocks.push_back(b);
  };
  report("setup", k.setup.ops());
  report("raster", k.raster.ops());
  if (k.parallax) report("parallax", k.parallax->ops());
  report("normal_interp", k.normal_interp.ops());
  if (k.bump_fetch) report("bump_fetch", k.bump_fetch->ops());
  if (k.bump_perturb) report("bump_perturb", k.bump_perturb->ops());
  if (k.normal_mux) report("normal_mux", k.normal_mux->ops());
  report("normalize", k.normalize.ops());
  if (k.vector_interp) report("vector_interp", k.vector_interp->ops());
  if (k.texture_fetch) report("texture_fetch", k.texture_fetch->ops());
  report("lighting", k.lighting.ops());
  report("framebuffer", k.framebuffer.ops());
  if (k.texel_project) report("texel_project", k.texel_project->ops());
  fill_counts(r, k);
  r.frame = std::move(k.framebuffer.frame());
  return r;
}

RenderResult render_systemc(const core::Scene& scene, const Inspect& inspect) {
  const Options o = read_options(scene);
  Kernels k(scene, o);
  return run_systemc(k, o, inspect);
}

RenderResult run_systemc(Kernels& k, const Options& o, const Inspect& inspect) {
  if (inspect.progress) k.setup.set_progress(inspect.progress);
  const core::Camera& camera = k.setup.scene().camera;
  Top top("shadetlm", k, o, inspect, camera.width, camera.height);
  // One quantum of 10 000 cycles: the source yields rarely, and never per pixel.
  tlm_utils::tlm_quantumkeeper::set_global_quantum(sc_core::sc_time(1e4 / o.clock_mhz, sc_core::SC_US));
  RenderResult r;
  r.engine = "systemc";
  r.clock_mhz = o.clock_mhz;
  const auto start = std::chrono::steady_clock::now();
  sc_core::sc_start();
  r.wall_s = seconds_since(start);
  for (BlockInfo* b : top.blocks()) {
    BlockReport br;
    br.name = b->block_name();
    br.stats = b->stats();
    br.timing = b->schedule().timing();
    br.free_cycle = b->schedule().free_cycle();
    br.busy_per_bin = b->schedule().busy_per_bin();
    r.frame_cycles = std::max(r.frame_cycles, br.free_cycle + br.timing.latency);
    r.blocks.push_back(br);
  }
  fill_counts(r, k);
  r.bin_cycles = inspect.bin_cycles;
  if (top.tracer() && std::filesystem::exists(inspect.vcd)) {
    r.trace_records = top.tracer()->records();
    const double ps = 1e6 / o.clock_mhz;
    write_gtkw(inspect.vcd.substr(0, inspect.vcd.size() - 4) + ".gtkw", inspect.vcd, top.tracer()->probes(),
               double(top.tracer()->first_cycle()) * ps, double(top.tracer()->last_cycle()) * ps);
  }
  if (!inspect.timeline.empty()) top.timeline_slices().write(inspect.timeline, top.names(), o.clock_mhz);
  for (const auto& b : r.blocks)
    if (b.name == "framebuffer") r.pixels_shaded = b.stats.pixels;
  r.frame = std::move(k.framebuffer.frame());
  return r;
}

void write_gtkw(const std::string& path, const std::string& vcd, const std::vector<Tracer::ProbeInfo>& probes,
                double from_ps, double to_ps) {
  // GTKWave's save format: "@<flags in hex>" sets how the following signals are
  // drawn, "-text" is a comment line. 28 = binary, right-justified (a 1-bit valid);
  // 24 = decimal; 8420 = analog step, signed, right-justified (real values).
  core::write_atomically(path, [&](const std::string& tmp) {
    std::ofstream out(tmp);
    out << "[*] shadetlm: the blocks in pipeline order\n"
        << "[dumpfile] \"" << std::filesystem::absolute(vcd).string() << "\"\n"
        << "[savefile] \"" << std::filesystem::absolute(path).string() << "\"\n"
        << "[timestart] " << uint64_t(from_ps) << "\n[size] 1400 900\n[sst_width] 200\n[signals_width] 240\n"
        << "[sst_expanded] 1\n";
    // Zoom: GTKWave 3.3 shows about 4.3·2^-zoom time units (ps here) across its default
    // wave pane (measured through its Tcl interface); show the traced span and 5 % more
    // (the dump runs 10 % past it: a window past the dump's end resets the start).
    const double zoom = -std::log2(std::max(1.0, (to_ps - from_ps) * 1.05 / 4.3));
    out << "*" << std::fixed << zoom << " -1\n";
    for (const auto& p : probes) {
      out << "@800200\n-" << p.block << "\n";  // a group per block
      for (size_t k = 0; k < p.names.size(); ++k) {
        if (k == 0) out << "@28\n" << p.names[k] << "\n";
        else if (!p.is_real[k]) out << "@24\n" << p.names[k] << "[31:0]\n";
        else out << "@8420\n" << p.names[k] << "\n@20000\n-\n";  // analog, one blank row of height
      }
      out << "@1000200\n-" << p.block << "\n";  // group end
    }
    if (!out) throw std::runtime_error(path + ": cannot write the GTKWave save file");
  });
}

const BlockReport* RenderResult::bottleneck() const {
  const BlockReport* best = nullptr;
  for (const auto& b : blocks)
    if (!best || b.stats.busy_cycles > best->stats.busy_cycles) best = &b;
  return best;
}

Ops RenderResult::total_ops() const {
  Ops o;
  for (const auto& b : blocks) o += b.stats.ops;
  return o;
}

nlohmann::json RenderResult::stats_json() const {
  nlohmann::json j;
  j["engine"] = engine;
  j["wall_s"] = wall_s;
  j["clock_mhz"] = clock_mhz;
  j["frame_cycles"] = frame_cycles;
  j["sim_time_s"] = double(frame_cycles) / (clock_mhz * 1e6);
  j["bottleneck"] = frame_cycles > 0 && bottleneck() ? nlohmann::json(bottleneck()->name) : nlohmann::json();
  j["precompute_s"] = precompute_s;
  j["nonfinite_replaced"] = nonfinite_replaced;
  j["elaborated"] = nlohmann::json::array();
  for (const auto& b : blocks) j["elaborated"].push_back(b.name);
  j["triangles"] = {{"in", triangles_in}, {"drawn", triangles_drawn}};
  j["pixels"] = {{"walked", pixels_walked}, {"hidden", pixels_hidden}, {"shaded", pixels_shaded}};
  j["blocks"] = nlohmann::json::object();
  // Every block's non-finite outputs and number events, summed (docs/numerical-stability.md).
  nlohmann::json numbers = {{"nonfinite", uint64_t(0)}, {"overflows", uint64_t(0)}, {"invalid", uint64_t(0)}};
  for (const auto& b : blocks) {
    nlohmann::json bj = {{"packets", b.stats.packets},     {"pixels", b.stats.pixels},
                         {"bypassed", b.stats.bypassed},   {"busy_cycles", b.stats.busy_cycles},
                         {"latency", b.timing.latency},    {"ii", b.timing.ii},
                         {"ops", b.stats.ops.to_json()}};
    bj["utilization"] = frame_cycles > 0 ? double(b.stats.busy_cycles) / double(frame_cycles) : 0.0;
    if (!b.ranges.empty()) bj["ranges"] = to_json(b.ranges);
    if (!b.details.is_null()) bj["details"] = b.details;
    if (b.numbers) {
      bj["numbers"] = {{"format", b.numbers->format},
                       {"nonfinite", b.numbers->counted ? nlohmann::json(b.numbers->nonfinite) : nlohmann::json()},
                       {"overflows", b.numbers->events.overflows}, {"invalid", b.numbers->events.invalid}};
      numbers["nonfinite"] = numbers["nonfinite"].get<uint64_t>() + b.numbers->nonfinite;
      numbers["overflows"] = numbers["overflows"].get<uint64_t>() + b.numbers->events.overflows;
      numbers["invalid"] = numbers["invalid"].get<uint64_t>() + b.numbers->events.invalid;
    }
    j["blocks"][b.name] = bj;
  }
  j["numbers"] = numbers;
  if (bin_cycles > 0 && frame_cycles > 0) {
    // Utilization over time: each block's busy share of every bin, and the busiest
    // block per bin. No back-pressure in the timing model, so no stalls: a block is
    // busy or waiting for input (a bubble).
    nlohmann::json over_time = {{"bin_cycles", bin_cycles}, {"blocks", nlohmann::json::object()}};
    const size_t bins = size_t((frame_cycles + bin_cycles - 1) / bin_cycles);
    std::vector<std::pair<uint64_t, std::string>> busiest(bins, {0, ""});
    for (const auto& b : blocks) {
      std::vector<double> share(bins, 0.0);
      for (size_t i = 0; i < bins && i < b.busy_per_bin.size(); ++i) {
        const uint64_t length = std::min<uint64_t>(bin_cycles, frame_cycles - i * bin_cycles);  // last one partial
        share[i] = double(b.busy_per_bin[i]) / double(length);
        if (b.busy_per_bin[i] > busiest[i].first) busiest[i] = {b.busy_per_bin[i], b.name};
      }
      over_time["blocks"][b.name] = share;
      j["blocks"][b.name]["idle_cycles"] = frame_cycles - b.stats.busy_cycles;
    }
    nlohmann::json names = nlohmann::json::array();
    for (const auto& [busy, name] : busiest) names.push_back(busy > 0 ? nlohmann::json(name) : nlohmann::json());
    over_time["bottleneck"] = names;
    j["utilization_over_time"] = over_time;
  }
  const nlohmann::json total = total_ops().to_json();
  j["ops"] = total;
  nlohmann::json per_pixel;
  const double n = pixels_shaded > 0 ? double(pixels_shaded) : 1.0;
  for (const auto& [kind, count] : total.items()) per_pixel[kind] = count.get<double>() / n;
  j["ops_per_shaded_pixel"] = per_pixel;
  return j;
}

}  // namespace modules
