// shadetlm render [SCENE] [-o frame.exr] [--preview frame.png] [--heat-map iterations.png] [--stats stats.json]
//                 [--compare-reference] [--engine systemc|loop] [--set key=value ...]
#include <cctype>
#include <chrono>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>

#include <unistd.h>

#include "app/commands.hpp"
#include "app/map_cache.hpp"
#include "app/progress.hpp"
#include "shadetlm/core/compare.hpp"
#include "shadetlm/core/input_error.hpp"
#include "shadetlm/modules/normalize/normalize_settings.hpp"
#include "shadetlm/modules/pipeline/pipeline.hpp"
#include "shadetlm/reference/reference.hpp"

namespace shadetlm::app {

namespace {

// Error of the pipeline's frame against the golden model's, per layer (over the pixels
// covered in either frame, and frame-wide), the coverage, and the truth the model used.
nlohmann::json error_against_reference(const core::Frame& frame, const core::Scene& scene, double* reference_s) {
  const auto start = std::chrono::steady_clock::now();
  const core::Frame ref = reference::to_frame(reference::render(scene, threads()), threads());
  *reference_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  core::CompareOptions o;
  o.fail = 0;  // report, do not judge
  o.threads = threads();
  const core::CompareResult r = core::compare_frames(frame, ref, o);
  nlohmann::json j;
  for (const auto& m : r.layers) {
    std::string key = m.layer;
    std::transform(key.begin(), key.end(), key.begin(), [](char c) { return char(std::tolower(c)); });
    j[key] = core::layer_json(m);
  }
  j["coverage"] = core::coverage_json(r.coverage);
  j["coverage_mismatches"] = r.coverage.differ;
  j["truth"] = reference::truth(scene);
  return j;
}
}  // namespace

// "x0,y0,x1,y1" (inclusive pixel bounds) and "i..j" (triangle ids, inclusive).
void parse_region(const std::string& text, modules::TraceRegion& r) {
  int v[4];
  char end;
  if (std::sscanf(text.c_str(), "%d,%d,%d,%d%c", &v[0], &v[1], &v[2], &v[3], &end) != 4 || v[0] > v[2] ||
      v[1] > v[3] || v[0] < 0 || v[1] < 0)
    throw core::InputError("--trace-region", text, "expected x0,y0,x1,y1 with 0 <= x0 <= x1 and 0 <= y0 <= y1");
  r.x0 = v[0], r.y0 = v[1], r.x1 = v[2], r.y1 = v[3];
}
void parse_triangles(const std::string& text, modules::TraceRegion& r) {
  unsigned long a, b;
  char end;
  if (std::sscanf(text.c_str(), "%lu..%lu%c", &a, &b, &end) != 2 || a > b || b > UINT32_MAX)
    throw core::InputError("--trace-triangles", text, "expected i..j with i <= j");
  r.triangle_first = uint32_t(a), r.triangle_last = uint32_t(b);
}

namespace {

// The render command's options, as the command line sets them.
struct RenderOptions {
  SceneOptions scene;
  std::string output = "out/frame.exr", preview, heat_map, stats, engine = "systemc";
  float heat_max = 32;
  bool compare = false, allow_nonfinite = false, allow_overflow = false;
  std::string vcd, region, triangles, timeline, timing_log, vectors;
  std::string map_cache;  // parallax maps kept here (app/map_cache.hpp)
};

// What the run records for inspection (waveforms, timeline, traced region and triangles),
// from the options; throws if they name it wrongly or this build or engine cannot record it.
modules::Inspect inspection_of(const RenderOptions& opt, const core::Scene& scene) {
  modules::Inspect inspect;
  inspect.vcd = opt.vcd;
  if (!opt.stats.empty()) inspect.bin_cycles = 10000;  // utilization over time, in the statistics
  inspect.timeline = opt.timeline;
  inspect.timing_log = !opt.timing_log.empty();
  inspect.vectors = opt.vectors;
  if (!opt.region.empty()) {
    parse_region(opt.region, inspect.region), inspect.region_given = true;
    if (inspect.region.x0 >= scene.camera.width || inspect.region.y0 >= scene.camera.height)
      throw core::InputError("--trace-region", opt.region,
                             "lies wholly outside the " + std::to_string(scene.camera.width) + "x" +
                                 std::to_string(scene.camera.height) + " frame: nothing would be traced");
  }
  if (!opt.triangles.empty()) {
    if (!inspect.region_given)
      inspect.region = {0, 0, scene.camera.width - 1, scene.camera.height - 1}, inspect.region_given = true;
    parse_triangles(opt.triangles, inspect.region);
    uint64_t triangles = 0;
    for (const auto& o : scene.objects) triangles += o.mesh.triangles.size();
    if (inspect.region.triangle_first >= triangles)
      throw core::InputError("--trace-triangles", opt.triangles,
                             "starts past the scene's last triangle (" + std::to_string(triangles) + " triangles)");
  }
  if (!inspect.vcd.empty() && (inspect.vcd.size() < 5 || !has_extension(inspect.vcd, ".vcd")))
    throw core::InputError("--vcd", inspect.vcd, "the waveform file must end in .vcd");
  if (!inspect.timeline.empty() && !has_extension(inspect.timeline, ".json") && !has_extension(inspect.timeline, ".html"))
    throw core::InputError("--timeline", inspect.timeline,
                           "the timeline is written as .json (trace events) or .html (the offline viewer)");
  for (const auto& [option, path] : {std::pair{"--vcd", inspect.vcd}, std::pair{"--timeline", inspect.timeline}})
    if (!modules::kTracing && !path.empty())
      throw core::InputError(option, path, "this build has tracing compiled out (SHADETLM_TRACING=OFF)");
  if (opt.engine == "loop" && (!inspect.vcd.empty() || !inspect.timeline.empty() || inspect.timing_log ||
                               !inspect.vectors.empty()))
    throw core::InputError("--engine", "loop",
                           "waveforms, timelines, timing logs and test vectors need the systemc engine");
  return inspect;
}

// The GTKWave view written beside the waveforms ("" without waveforms).
std::string gtkw_path_of(const std::string& vcd) {
  return vcd.empty() ? "" : vcd.substr(0, vcd.size() - 4) + ".gtkw";
}

// The checks that can still refuse the run once its inspection is known: a heat map
// needs something to map, and every output must be writable.
void check_before_simulation(const RenderOptions& opt, const core::Scene& scene, const modules::Inspect& inspect) {
  // Checked before the simulation: nothing may throw after sc_start in normal
  // course (under ASan, unwinding past SystemC's coroutines is not supported).
  if (!opt.heat_map.empty() &&
      std::none_of(scene.objects.begin(), scene.objects.end(), [&](const core::Object& o) {
        return scene.materials[size_t(o.material)].path == core::ShadingPath::Parallax;
      }))
    throw core::InputError("--heat-map", opt.heat_map, "the scene has no parallax material: no iterations to map");
  require_output("--output", opt.output);
  std::vector<std::pair<std::string, std::string>> outputs = {{"--output", opt.output},
                                                              {"--preview", opt.preview},
                                                              {"--heat-map", opt.heat_map},
                                                              {"--stats", opt.stats},
                                                              {"--vcd", inspect.vcd},
                                                              {"--vcd", gtkw_path_of(inspect.vcd)},
                                                              {"--timeline", inspect.timeline},
                                                              {"--timing-log", opt.timing_log}};
  if (!inspect.vectors.empty())
    for (const auto& f : modules::vector_files(modules::standard_pipeline(), inspect.vectors))
      outputs.push_back({"--vectors", f});
  check_outputs(outputs, scene.inputs);
  if (!opt.map_cache.empty()) check_map_cache(opt.map_cache, outputs);
  // The traced pixels: the region's part of the frame.
  const modules::TraceRegion& r = inspect.region;
  const int64_t width = scene.camera.width, height = scene.camera.height;
  const int64_t across = std::min<int64_t>(r.x1, width - 1) - r.x0 + 1, down = std::min<int64_t>(r.y1, height - 1) - r.y0 + 1;
  const uint64_t traced = inspect.vcd.empty() && inspect.timeline.empty() ? 0
                          : inspect.region_given ? uint64_t(std::max<int64_t>(across, 0) * std::max<int64_t>(down, 0))
                                                 : uint64_t(width * height);
  take_run_memory(scene, true, opt.compare, traced);
  // Test vectors come from the kernels, and are kept in memory (about 100 bytes a pixel).
  if (!inspect.vectors.empty()) {
    const core::Settings settings = scene.pipeline.resolve(modules::standard_pipeline().all_settings());
    if (modules::read_settings<modules::NormalizeSettings>(settings).impl == modules::NormalizeSettings::Impl::Rtl)
      throw core::InputError("--vectors", inspect.vectors,
                             "test vectors are the kernel's words: render with pipeline.normalize.impl=kernel");
    const uint64_t pixels = inspect.region_given ? uint64_t(std::max<int64_t>(across, 0) * std::max<int64_t>(down, 0))
                                                 : uint64_t(width * height);
    if (pixels > (uint64_t(1) << 20))
      throw core::InputError("--vectors", inspect.vectors,
                             "test vectors are for regions of at most 1048576 pixels: give a --trace-region");
  }
  // The log is kept in memory during the run (about 100 bytes a pixel and block): for
  // the small frames the timing check is for.
  constexpr int64_t kMaxLoggedPixels = 1 << 20;
  if (!opt.timing_log.empty() && int64_t(scene.camera.width) * scene.camera.height > kMaxLoggedPixels)
    throw core::InputError("--timing-log", opt.timing_log,
                           "a timing log is for frames of at most 1048576 pixels (the scene's camera.resolution is " +
                               std::to_string(scene.camera.width) + "x" + std::to_string(scene.camera.height) + ")");
}

// Renders the scene on the engine named ("loop" or "systemc"), its share done shown.
modules::RenderResult render_with_progress(const core::Scene& scene, const std::string& engine,
                                           modules::Inspect inspect, Progress& progress) {
  progress.phase("pipeline", "pipeline");
  inspect.progress = [&progress, halfway = false](double share) mutable {
    progress.share(share);
    if (!halfway && share >= 0.5) halfway = true, core::pause_point("pipeline half");
  };
  return engine == "loop" ? modules::render_loop(scene, inspect) : modules::render_systemc(scene, inspect);
}

// The run's statistics: the engine's, the scene and its resolved configuration, and with
// --compare-reference the error against the golden model (whose time goes to *reference_s).
// The pixels the frame covers (A > 0), each once: beside the shaded ones, which count
// every pixel as often as it was shaded (overdraw).
uint64_t covered_pixels(const core::Frame& frame) {
  uint64_t covered = 0;
  if (const auto* a = frame.find("A"))
    for (float v : a->values) covered += v > 0;
  return covered;
}

nlohmann::json statistics_of(const RenderOptions& opt, const modules::RenderResult& r, const core::Scene& scene,
                             double* reference_s) {
  nlohmann::json stats = r.stats_json();
  stats["pixels"]["covered"] = covered_pixels(r.frame);  // (shaded counts overdraw; covered, the frame's)
  stats["scene"] = scene.file;
  stats["config"] = settings_of(scene).resolved();
  if (opt.compare) stats["error"] = error_against_reference(r.frame, scene, reference_s);
  return stats;
}

// The phases' times so far, {"load": s, "pipeline": s, …} (Progress::seconds).
nlohmann::json phase_times(const Progress& progress) {
  nlohmann::json times = nlohmann::json::object();
  for (const auto& [key, seconds] : progress.seconds()) times[key] = seconds;
  return times;
}

// What the timing log was rendered from, for the timing check to derive the walks from:
// `scene <file>` (none: the built-in demo) and a `set <key=value>` record per override.
std::string timing_log_head(const SceneOptions& scene) {
  std::string head = "scene " + scene.scene + "\n";
  for (const std::string& s : scene.overrides) head += "set " + s + "\n";
  return head;
}

// Writes the frame, its preview and heat map, the timing log and the statistics (with
// the phases' times: "write" so far is encoding and writing everything before them)
// beside the inspection files the pipeline wrote into `outputs`, and commits them all:
// all appear, or none (a failed write, a signal: the temporaries go with `outputs`).
void write_outputs(const RenderOptions& opt, const modules::RenderResult& r, nlohmann::json& stats,
                   core::OutputSet& outputs, const Progress& progress) {
  add_frame(outputs, r.frame, opt.output, opt.preview, opt.heat_map, opt.heat_max);
  if (!opt.timing_log.empty()) outputs.write(opt.timing_log, timing_log_head(opt.scene) + r.timing_log);
  stats["phases_s"] = phase_times(progress);
  // (text from the command line need not be UTF-8: replaced, not refused after the render)
  if (!opt.stats.empty()) outputs.write(opt.stats, stats.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
  outputs.commit();
}

// "  phases: load 0.01 s, pipeline 0.15 s, golden_model 0.4 s, write 0.09 s (2 threads)"
void print_phases(const Progress& progress) {
  std::cout << "  phases:";
  const char* separator = " ";
  for (const auto& [key, seconds] : progress.seconds())
    std::cout << separator << key << " " << core::figure(seconds) << " s", separator = ", ";
  std::cout << " (" << threads() << " threads for the golden model and EXR compression)\n";
}

// Saturations, overflows and invalid operations that the blocks' number formats met,
// said per block on stderr; exit status 3 unless the user accepts them (--allow-overflow),
// as for non-finite values: a frame computed through a saturated datapath is not the
// algorithm's answer.
int number_events_status(const modules::RenderResult& r, bool allowed) {
  bool any = false;
  for (const auto& b : r.blocks) {
    if (!b.numbers || (b.numbers->events.overflows == 0 && b.numbers->events.invalid == 0)) continue;
    std::cerr << "shadetlm: " << b.name << " (" << b.numbers->format << "): " << b.numbers->events.overflows
              << " results saturated or overflowed, " << b.numbers->events.invalid
              << " invalid operations (blocks." << b.name << ".numbers in --stats)\n";
    any = true;
  }
  if (!any) return 0;
  if (!allowed) std::cerr << "shadetlm: exit status 3: a number format overflowed (--allow-overflow accepts it)\n";
  return allowed ? 0 : kExitNonfinite;
}

// The summary's lines on the error against the golden model (stats["error"]).
void print_error(const nlohmann::json& e, double reference_s) {
  const auto fig = [](const nlohmann::json& x) { return x.is_number() ? core::figure(x.get<double>()) : x.get<std::string>(); };
  const nlohmann::json& c = e["coverage"];
  std::cout << "  error against the golden model over the " << c["either"] << " pixels covered in either frame ("
            << c["differ"] << " covered in one only); golden model " << core::figure(reference_s) << " s\n";
  for (const char* layer : {"rgb", "z", "n"})
    if (e.contains(layer)) {
      const nlohmann::json& m = e[layer];
      std::cout << "  error " << layer << ": max " << fig(m["max"]) << " at (" << m["max_at"][0] << ", "
                << m["max_at"][1] << "), rmse " << fig(m["rmse"]) << ", psnr " << fig(m["psnr"])
                << " dB; frame-wide: rmse " << fig(m["frame"]["rmse"]) << ", psnr " << fig(m["frame"]["psnr"]) << " dB\n";
    }
  std::string truth;
  for (const auto& [material, what] : e["truth"].items()) truth += (truth.empty() ? "" : ", ") + material + ": " + what.get<std::string>();
  std::cout << "  golden model's truth: " << (truth.empty() ? "the shading model" : truth) << "\n";
}

// The silicon of the blocks' arithmetic (docs/silicon.md): the total, then each block's
// area, largest first; the blocks whose format has no figure named with the reason.
void print_silicon(const nlohmann::json& stats) {
  const nlohmann::json& s = stats["silicon"];
  std::cout << "  silicon (" << s["node"].get<std::string>() << ", arithmetic only): "
            << (s["area_mm2"].is_null() ? "area needs the systemc engine" : core::figure(s["area_mm2"].get<double>()) + " mm2")
            << ", "
            << (s["energy_nj_per_shaded_pixel"].is_null()
                    ? std::string("no pixel shaded")
                    : core::figure(s["energy_nj_per_shaded_pixel"].get<double>()) + " nJ a shaded pixel");
  if (!s["power_mw"].is_null())
    std::cout << ", " << core::figure(s["power_mw"].get<double>()) << " mW at "
              << core::figure(stats["clock_mhz"].get<double>()) << " MHz";
  std::cout << "\n";
  std::vector<std::pair<double, std::string>> areas;
  for (const auto& [name, b] : stats["blocks"].items()) {
    const nlohmann::json& bs = b["silicon"];
    if (!bs["priced"].get<bool>())
      std::cout << "  silicon of " << name << " not priced: " << bs["why"].get<std::string>() << "\n";
    else if (!bs["area_mm2"].is_null() && bs["area_mm2"].get<double>() > 0)
      areas.emplace_back(bs["area_mm2"].get<double>(), name);
  }
  std::sort(areas.rbegin(), areas.rend());
  std::string line;
  for (const auto& [area, name] : areas) line += (line.empty() ? "" : ", ") + name + " " + core::figure(area);
  if (!line.empty()) std::cout << "    area by block, mm2: " << line << "\n";
}

// The run's summary on stdout: what was rendered, how long it took, the error and what was written.
void print_summary(const RenderOptions& opt, const core::Scene& scene, const modules::RenderResult& r,
                   const nlohmann::json& stats, const modules::Inspect& inspect, double reference_s) {
  std::cout << "render (" << r.engine << "): " << scene.file << ", " << scene.camera.width << "x"
            << scene.camera.height << ", " << r.triangles_drawn << " of " << r.triangles_in << " triangles drawn, "
            << r.pixels_shaded << " pixels shaded (overdraw counted), " << stats["pixels"]["covered"].get<uint64_t>()
            << " covered, " << core::figure(r.wall_s) << " s\n";
  if (r.frame_cycles > 0)
    std::cout << "  " << r.frame_cycles << " cycles at " << core::figure(r.clock_mhz) << " MHz ("
              << core::figure(stats["sim_time_s"].get<double>() * 1e3) << " ms simulated), bottleneck "
              << stats["bottleneck"].get<std::string>() << "\n";
  print_silicon(stats);
  if (opt.compare) print_error(stats["error"], reference_s);
  if (!inspect.vcd.empty())
    std::cout << "  traced " << r.trace_records << " pixel outputs into " << inspect.vcd << " (view: gtkwave "
              << inspect.vcd << " " << gtkw_path_of(inspect.vcd) << ")\n";
  if (!inspect.timeline.empty()) std::cout << "  timeline: " << inspect.timeline << "\n";
  if (!inspect.vectors.empty())
    std::cout << "  test vectors of " << r.vector_pixels << " pixels into " << inspect.vectors << "\n";
  std::cout << "  wrote " << opt.output << (opt.preview.empty() ? "" : " and " + opt.preview)
            << (opt.heat_map.empty() ? "" : " and " + opt.heat_map)
            << (opt.stats.empty() ? "" : " and " + opt.stats) << "\n";
}

}  // namespace

Command add_render_command(CLI::App& app) {
  auto opt = std::make_shared<RenderOptions>();
  CLI::App* cmd = app.add_subcommand("render", "render a scene through the SystemC/TLM-2.0 pipeline");
  opt->scene.add_to(*cmd);
  cmd->add_option("-o,--output", opt->output, "EXR frame to write")->capture_default_str()
      ->check(kNotEmpty)
      ->check(kExrPath);
  cmd->add_option("--preview", opt->preview, "also write an sRGB PNG preview (FILE.png)")
      ->check(kNotEmpty)
      ->check(kPngPath);
  cmd->add_option("--heat-map", opt->heat_map,
                  "write the parallax iterations per pixel as a heat map PNG (black 0 … white --heat-max and more)")
      ->check(kNotEmpty)
      ->check(kPngPath);
  cmd->add_option("--heat-max", opt->heat_max, "iterations shown white in the heat map")
      ->capture_default_str()
      ->check(finite_in(1.0, 1e6));
  cmd->add_option("--stats", opt->stats, "write statistics (time, cycles, operations, error) as JSON")
      ->check(kNotEmpty);
  cmd->add_flag("--compare-reference", opt->compare, "also render the golden model and report the error");
  cmd->add_flag("--allow-nonfinite", opt->allow_nonfinite,
                "exit 0 even when NaN or infinite values reached the frame (written as 0; else exit status 3)");
  cmd->add_flag("--allow-overflow", opt->allow_overflow,
                "exit 0 even when a block's number format saturated, overflowed or met an invalid operation "
                "(said per block; else exit status 3)");
  cmd->add_option("--engine", opt->engine,
                  "systemc: the TLM-2.0 model; loop: the same kernels in a plain C++ loop (no timing)")
      ->check(CLI::IsMember({"systemc", "loop"}))
      ->capture_default_str();
  cmd->add_option("--vcd", opt->vcd, "waveforms of the blocks (VCD), with a GTKWave view (.gtkw) beside them")
      ->check(kNotEmpty);
  cmd->add_option("--trace-region", opt->region, "pixels traced into the VCD and the timeline: x0,y0,x1,y1")
      ->check(kNotEmpty);
  cmd->add_option("--trace-triangles", opt->triangles, "triangles traced: i..j (ids in drawing order)")
      ->check(kNotEmpty);
  cmd->add_option("--vectors", opt->vectors,
                  "test vectors of the traced region: <folder>/<block>.in.hex and .out.hex (docs/rtl.md)")
      ->check(kNotEmpty);
  cmd->add_option("--timeline", opt->timeline,
                  "transaction timeline: FILE.html, a page that views it offline, or FILE.json, Chrome trace events")
      ->check(kNotEmpty);
  cmd->add_option("--timing-log", opt->timing_log,
                  "every pixel's start and hand-over cycle at every block, for `shadetlm timing-check`")
      ->check(kNotEmpty);
  cmd->add_option("--map-cache", opt->map_cache,
                  "a folder of parallax maps: read from it, built into it once (default: $SHADETLM_MAP_CACHE)")
      ->envname("SHADETLM_MAP_CACHE")
      ->check(kNotEmpty);
  return {cmd, [opt]() {
            Progress progress("render");
            progress.phase("loading the scene", "load");
            core::Scene scene = opt->scene.load();
            modules::Inspect inspect = inspection_of(*opt, scene);
            check_before_simulation(*opt, scene, inspect);
            core::OutputSet outputs;  // every file of the run, committed together at its end
            inspect.outputs = &outputs;
            if (!opt->map_cache.empty()) {
              progress.phase("parallax maps (cache)", "maps");
              use_map_cache(scene, opt->map_cache);
            }
            modules::RenderResult r = render_with_progress(scene, opt->engine, inspect, progress);
            double reference_s = 0;
            progress.phase(opt->compare ? "golden model" : "statistics", opt->compare ? "golden_model" : "statistics");
            nlohmann::json stats = statistics_of(*opt, r, scene, &reference_s);
            describe(r.frame, scene, opt->scene, opt->engine == "loop" ? "pipeline-loop" : "pipeline");
            progress.phase("writing", "write");
            write_outputs(*opt, r, stats, outputs, progress);
            progress.done();
            print_summary(*opt, scene, r, stats, inspect, reference_s);
            print_phases(progress);
            const int nonfinite = nonfinite_status(r.nonfinite_replaced, opt->allow_nonfinite);
            const int overflow = number_events_status(r, opt->allow_overflow);
            return std::max(nonfinite, overflow);
          }};
}

}  // namespace shadetlm::app
