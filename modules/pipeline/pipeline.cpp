#include "modules/pipeline/pipeline.hpp"

#include <chrono>
#include <functional>

#include "core/input_error.hpp"
#include "modules/raster/raster.hpp"
#include "modules/setup/setup.hpp"

namespace modules {

const std::vector<std::string>& block_names() {
  static const std::vector<std::string> names = {"setup",         "raster",        "normal_interp",
                                                 "normalize",     "vector_interp", "texture_fetch",
                                                 "lighting",      "framebuffer"};
  return names;
}

Options read_options(const core::Scene& scene) {
  if (scene.lights.size() > size_t(kMaxLights))
    throw core::InputError(scene.file, "lights",
                           "the pipeline's lighting datapath holds at most " + std::to_string(kMaxLights) +
                               " lights, the scene has " + std::to_string(scene.lights.size()));
  Options o;
  o.perspective = scene.pipeline.string("normal_interp.mode") == "perspective";
  o.normalize = parse_normalize_mode(scene.pipeline.string("normalize.mode"));
  o.clock_mhz = scene.pipeline.number("clock_mhz");
  for (const auto& b : block_names())
    o.timing[b] = Timing{uint64_t(scene.pipeline.integer(b + ".latency")),
                         uint64_t(scene.pipeline.integer(b + ".ii"))};
  return o;
}

Kernels::Kernels(const core::Scene& scene, const Options& o)
    : setup(scene, o.perspective),
      raster(scene.camera.width, scene.camera.height),
      normalize(o.normalize),
      lighting(scene),
      framebuffer(scene) {
  if (VectorInterpKernel::needed(scene)) vector_interp.emplace(scene, setup.point_lights());
  if (TextureFetchKernel::needed(scene)) texture_fetch.emplace(scene);
}

namespace {

void fill_counts(RenderResult& r, const Kernels& k) {
  r.triangles_in = k.setup.triangles_in();
  r.triangles_drawn = k.setup.triangles_out();
  r.pixels_walked = k.raster.pixels_walked();
  r.pixels_hidden = k.raster.pixels_hidden();
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The SystemC top level: the blocks the scene needs, bound in a chain.
class Top : public sc_core::sc_module {
 public:
  Top(sc_core::sc_module_name name, Kernels& k, const Options& o)
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
    normal_interp_ = add(stage("normal_interp", k.normal_interp, o));
    normalize_ = add(stage("normalize", k.normalize, o));
    if (k.vector_interp) vector_interp_ = add(stage("vector_interp", *k.vector_interp, o));
    if (k.texture_fetch) texture_fetch_ = add(stage("texture_fetch", *k.texture_fetch, o));
    lighting_ = add(stage("lighting", k.lighting, o));
    // The framebuffer ends the chain: its output socket stays unbound.
    framebuffer_ = stage("framebuffer", k.framebuffer, o);
    bind_last(framebuffer_->in);
    blocks_.push_back(framebuffer_.get());
  }
  const std::vector<BlockInfo*>& blocks() const { return blocks_; }

 private:
  template <class K>
  std::unique_ptr<Stage<K>> stage(const char* name, K& kernel, const Options& o) {
    return std::make_unique<Stage<K>>(name, kernel, o.timing.at(name), period_);
  }

  sc_core::sc_time period_;
  std::unique_ptr<Setup> setup_;
  std::unique_ptr<Raster> raster_;
  std::unique_ptr<Stage<NormalInterpKernel>> normal_interp_;
  std::unique_ptr<Stage<NormalizeKernel>> normalize_;
  std::unique_ptr<Stage<VectorInterpKernel>> vector_interp_;
  std::unique_ptr<Stage<TextureFetchKernel>> texture_fetch_;
  std::unique_ptr<Stage<LightingKernel>> lighting_;
  std::unique_ptr<Stage<FramebufferKernel>> framebuffer_;
  std::vector<BlockInfo*> blocks_;
};

}  // namespace

RenderResult render_loop(const core::Scene& scene) {
  const Options o = read_options(scene);
  Kernels k(scene, o);
  RenderResult r;
  r.engine = "loop";
  r.clock_mhz = o.clock_mhz;
  const auto start = std::chrono::steady_clock::now();
  k.setup.run([&](const TriangleSetup& t) {
    k.raster.run(t, [&](SpanPacket& p) {
      k.normal_interp.process(p);
      k.normalize.process(p);
      if (k.vector_interp) k.vector_interp->process(p);
      if (k.texture_fetch && !k.texture_fetch->bypass(p)) k.texture_fetch->process(p);
      k.lighting.process(p);
      k.framebuffer.process(p);
      r.pixels_shaded += uint64_t(p.count);
    });
  });
  r.wall_s = seconds_since(start);
  fill_counts(r, k);
  auto report = [&](const char* name, const Ops& ops) {
    BlockReport b;
    b.name = name;
    b.stats.ops = ops;
    b.timing = o.timing.at(name);
    r.blocks.push_back(b);
  };
  report("setup", k.setup.ops());
  report("raster", k.raster.ops());
  report("normal_interp", k.normal_interp.ops());
  report("normalize", k.normalize.ops());
  if (k.vector_interp) report("vector_interp", k.vector_interp->ops());
  if (k.texture_fetch) report("texture_fetch", k.texture_fetch->ops());
  report("lighting", k.lighting.ops());
  report("framebuffer", k.framebuffer.ops());
  r.frame = std::move(k.framebuffer.frame());
  return r;
}

RenderResult render_systemc(const core::Scene& scene) {
  const Options o = read_options(scene);
  Kernels k(scene, o);
  Top top("shadetlm", k, o);
  // One quantum of 10 000 cycles: the source yields rarely, and never per pixel.
  tlm_utils::tlm_quantumkeeper::set_global_quantum(sc_core::sc_time(1e4 / o.clock_mhz, sc_core::SC_US));
  RenderResult r;
  r.engine = "systemc";
  r.clock_mhz = o.clock_mhz;
  const auto start = std::chrono::steady_clock::now();
  sc_core::sc_start();
  r.wall_s = seconds_since(start);
  fill_counts(r, k);
  for (BlockInfo* b : top.blocks()) {
    BlockReport br;
    br.name = b->block_name();
    br.stats = b->stats();
    br.timing = b->schedule().timing();
    br.free_cycle = b->schedule().free_cycle();
    r.frame_cycles = std::max(r.frame_cycles, br.free_cycle + br.timing.latency);
    r.blocks.push_back(br);
  }
  r.pixels_shaded = r.blocks.back().stats.pixels;
  r.frame = std::move(k.framebuffer.frame());
  return r;
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
  j["triangles"] = {{"in", triangles_in}, {"drawn", triangles_drawn}};
  j["pixels"] = {{"walked", pixels_walked}, {"hidden", pixels_hidden}, {"shaded", pixels_shaded}};
  j["blocks"] = nlohmann::json::object();
  for (const auto& b : blocks) {
    nlohmann::json bj = {{"packets", b.stats.packets},     {"pixels", b.stats.pixels},
                         {"bypassed", b.stats.bypassed},   {"busy_cycles", b.stats.busy_cycles},
                         {"latency", b.timing.latency},    {"ii", b.timing.ii},
                         {"ops", b.stats.ops.to_json()}};
    bj["utilization"] = frame_cycles > 0 ? double(b.stats.busy_cycles) / double(frame_cycles) : 0.0;
    j["blocks"][b.name] = bj;
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
