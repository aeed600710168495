// shadetlm precompute boxgapmap|donnellymap|refinedmap|conemap|relaxedconemap HEIGHT -o map.exr [--slices D] …
// shadetlm parallax-bench [SCENE] [--material M] [--elevations 60,30,15,5] [--json out.json]
//
// The parallax paper's maps, and the measurement behind docs/parallax.md: every tracer
// on bundles of parallel view rays over the whole height map at a few view elevations,
// each ray checked against the golden model's exact first hit.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "app/progress.hpp"
#include "shadetlm/core/bump_map.hpp"
#include "shadetlm/core/compare.hpp"
#include "shadetlm/core/memory_budget.hpp"
#include "shadetlm/core/input_error.hpp"
#include "shadetlm/core/parallax_map.hpp"
#include "shadetlm/core/version.hpp"
#include "shadetlm/modules/parallax/parallax_kernel.hpp"
#include "shadetlm/reference/parallax.hpp"

namespace shadetlm::app {

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

void add_map_precompute(CLI::App* precompute, std::vector<std::pair<CLI::App*, std::function<int()>>>& runs) {
  struct Options {
    std::string height, output;
    int slices = 16, levels = 0;
    core::RefinedParams refined;
  };
  for (const char* kind : {"boxgapmap", "donnellymap", "refinedmap", "conemap", "relaxedconemap"}) {
    auto opt = std::make_shared<Options>();
    opt->output = std::string("out/") + kind + ".exr";
    const std::string k = kind;
    CLI::App* cmd = precompute->add_subcommand(
        kind, k == "boxgapmap"     ? "the box-gap distance map, safe for nearest reads (parallax, docs/parallax.md)"
              : k == "donnellymap" ? "Donnelly's Euclidean distance map, as published"
              : k == "refinedmap"  ? "the parallax paper's refined distance map"
              : k == "conemap"     ? "a safe cone map for cone stepping"
                                   : "a safe relaxed cone map for relaxed cone stepping");
    const bool cones = k == "conemap" || k == "relaxedconemap";
    if (k == "boxgapmap") cmd->alias("distancemap");  // its name before Donnelly's map was built
    cmd->add_option("height", opt->height, "height map image (first channel, clamped to [0, 1])")->required();
    cmd->add_option("-o,--output", opt->output, "EXR to write")->capture_default_str()
      ->check(kNotEmpty)
      ->check(kExrPath);
    cmd->add_option("--slices", opt->slices, "D: voxels across the relief's depth")
        ->capture_default_str()
        ->check(finite_in(1, 256));
    if (k == "refinedmap" || k == "relaxedconemap")
      cmd->add_option("--min-elevation", opt->refined.min_elevation_deg,
                      "lowest admissible view elevation, degrees, in the map's space (texels across, slices down)")
          ->capture_default_str()
          ->check(finite_in(0.1, 89.0));
    if (k == "refinedmap") {
      cmd->add_option("--azimuths", opt->refined.azimuths, "directions around")->capture_default_str()->check(
          finite_in(1, 256));
      cmd->add_option("--elevations", opt->refined.elevations, "elevations below the vertical")
          ->capture_default_str()
          ->check(finite_in(1, 64));
      cmd->add_option("--rays-per-texel", opt->refined.rays_per_texel, "parallel rays per texel side")
          ->capture_default_str()
          ->check(finite_in(1, 8));
      cmd->add_option("--margin", opt->refined.margin, "voxels taken off every ray-derived value")
          ->capture_default_str()
          ->check(finite_in(0.0, 64.0));
    }
    if (cones)
      cmd->add_option("--levels", opt->levels, "height levels the apexes round up to (default 4·slices)")
          ->check(finite_in(1, 4096));
    runs.push_back({cmd, [opt, k, cones]() {
                      Progress progress("precompute " + k);
                      progress.phase("loading the height map");
                      require_output("--output", opt->output);
                      check_outputs({{"--output", opt->output}}, {opt->height});
                      const core::Texture map = core::load_texture_file(opt->height);
                      core::check_height_map(map, opt->height, "");  // what a scene accepts of its height map
                      const core::HeightField f = core::height_field(map, opt->height, "");
                      const uint64_t volume = uint64_t(f.width) * uint64_t(f.height) * uint64_t(opt->slices) * 4;
                      core::MemoryBudget::process().take(cones ? volume / uint64_t(opt->slices) * 4
                                                         : volume * (k == "refinedmap" ? 2 : 1),
                                                         opt->height, "--slices");
                      progress.phase("building the " + k);
                      const auto start = std::chrono::steady_clock::now();
                      double seconds = 0;
                      auto stamp = [&](std::map<std::string, std::string>& params) {
                        params["shadetlm:version"] = core::kVersion;
                        params["shadetlm:height"] = opt->height;
                      };
                      if (cones) {
                        const int levels = opt->levels > 0 ? opt->levels : 4 * opt->slices;
                        core::ConeMap m = k == "conemap" ? core::cone_map(f, opt->slices, levels)
                                                         : core::relaxed_cone_map(f, opt->slices, levels,
                                                                                  opt->refined.min_elevation_deg);
                        seconds = seconds_since(start);
                        stamp(m.params);
                        progress.phase("writing");
                        core::write_cone_map(opt->output, m);
                      } else {
                        core::VolumeMap m = k == "donnellymap" ? core::donnelly_map(f, opt->slices)
                                                               : core::box_gap_map(f, opt->slices);
                        if (k == "refinedmap") m = core::refined_map(f, m, opt->refined);
                        seconds = seconds_since(start);
                        stamp(m.params);
                        progress.phase("writing");
                        core::write_volume_map(opt->output, m, m.params.at("shadetlm:map"));
                      }
                      progress.done();
                      std::cout << "precompute " << k << ": " << opt->height << " (" << f.width << "x" << f.height
                                << "), " << opt->slices << " slices, " << core::figure(seconds) << " s\n  wrote " << opt->output
                                << " (" << std::filesystem::file_size(opt->output) << " bytes)\n";
                      return 0;
                    }});
  }
}

namespace {

// The parallax-bench command's options, as the command line sets them.
struct BenchOptions {
  SceneOptions scene;
  std::string material, json;
  std::vector<double> elevations{60, 30, 15, 5};
  std::vector<double> margins;  // refined maps to measure; empty: the material's margin
  double azimuth = 30;
  int rays = 128;
};

// The parallax material measured: the one named (or the first), with a depth to measure.
const core::Material& parallax_material(const core::Scene& scene, const std::string& name) {
  const core::Material* mat = nullptr;
  for (const auto& m : scene.materials)
    if (m.path == core::ShadingPath::Parallax && (name.empty() || m.name == name)) {
      mat = &m;
      break;
    }
  if (!mat)
    throw core::InputError(scene.file, "materials", "no parallax material" + (name.empty() ? "" : " named " + name));
  if (!(mat->parallax.depth > 0)) throw core::InputError(scene.file, "parallax.depth", "must be > 0 to measure");
  return *mat;
}

// A tracer measured: its name in the figures and its settings.
struct Method {
  std::string name;
  core::ParallaxSettings s;
};

// The methods as a designer would line them up, each on the material's settings: the
// refined map once per margin asked ("refined m=0.5"), or at the material's ("refined").
std::vector<Method> methods_to_compare(const core::ParallaxSettings& base, const std::vector<double>& margins) {
  std::vector<Method> methods;
  auto with = [&](const std::string& name, core::ParallaxMethod m, core::DistanceMap map = core::DistanceMap::Refined) {
    core::ParallaxSettings s = base;
    s.method = m, s.map = map, s.cones = core::ConeKind::Classic;
    s.map_file.clear();  // each method's own map, built
    if (map == core::DistanceMap::Donnelly && m == core::ParallaxMethod::Distance) s.early_exit = false;  // as published
    methods.push_back({name, s});
  };
  with("offset", core::ParallaxMethod::Offset);
  with("steep", core::ParallaxMethod::Steep);
  with("pom", core::ParallaxMethod::Pom);
  with("relief", core::ParallaxMethod::Relief);
  with("donnelly", core::ParallaxMethod::Distance, core::DistanceMap::Donnelly);
  with("box-gap", core::ParallaxMethod::Distance, core::DistanceMap::BoxGap);
  if (margins.empty()) with("refined", core::ParallaxMethod::Distance);
  for (double margin : margins) {
    std::ostringstream name;
    name << "refined m=" << margin;
    with(name.str(), core::ParallaxMethod::Distance);
    methods.back().s.margin = margin;
  }
  with("cone", core::ParallaxMethod::Cone);
  with("relaxed cone", core::ParallaxMethod::Cone);
  methods.back().s.cones = core::ConeKind::Relaxed;
  return methods;
}

// The figures' header: what was measured, on which map and settings, with how many rays.
nlohmann::json bench_header(const BenchOptions& opt, const core::Scene& scene, const core::Material& mat,
                            const core::Texture& height) {
  const core::ParallaxSettings& base = mat.parallax;
  return {{"scene", scene.file},
          {"material", mat.name},
          {"height_map", height.name},
          {"size", {height.width, height.height}},
          {"depth", base.depth},
          {"slices", base.slices},
          {"min_elevation_deg", base.min_elevation_deg},
          {"margin", base.margin},
          {"max_iterations", base.max_iterations},
          {"layers", {base.layers_min, base.layers_max}},
          {"binary_steps", base.binary_steps},
          {"steps", base.steps},
          {"azimuth_deg", opt.azimuth},
          {"rays", opt.rays * opt.rays}};
}

// The maps built once for each method (one per method, in order), their times into out["precompute_s"].
std::vector<modules::ParallaxMaps> build_maps(const std::vector<Method>& methods, const core::Texture& height,
                                              const std::string& scene_file, nlohmann::json& out) {
  std::vector<modules::ParallaxMaps> maps;
  for (const auto& m : methods) {
    maps.push_back(modules::build_parallax_maps(height, m.s, scene_file));
    out["precompute_s"][m.name] = maps.back().precompute_s;
  }
  return maps;
}

// One view elevation: the rays' direction, and their entry points with the golden model's exact hits.
struct View {
  glm::dvec3 direction;                       // the rays' direction (golden model's space)
  double tracer_length = 0;                   // the ray's length in the tracer's space per unit of t
  double tracer_elevation_deg = 0;            // the elevation as the tracer sees it (texels, slices)
  std::vector<glm::dvec2> entries;            // where the rays enter, in uv
  std::vector<reference::ParallaxHit> exact;  // where each meets the relief first
};

// The rays of a view at `elevation` degrees (and `azimuth` degrees from the u axis), rays × rays of them.
View view_at(double elevation, double azimuth, int rays, const core::Texture& height,
             const core::ParallaxSettings& base) {
  const double pi = 3.14159265358979323846;
  const double W = height.width, H = height.height, D = base.slices;
  View view;
  const double el = elevation * pi / 180, az = azimuth * pi / 180;
  const glm::dvec3 d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), -std::sin(el));
  view.direction = d;
  // The ray's length in the tracer's space per unit of the golden model's t.
  view.tracer_length = glm::length(glm::dvec3(d.x * W, d.y * H, d.z * D / base.depth));
  view.tracer_elevation_deg = std::asin(-d.z * D / base.depth / view.tracer_length) * 180 / pi;
  // The entry points: a grid over the map, jittered within its cells (fixed hash).
  for (int j = 0; j < rays; ++j)
    for (int i = 0; i < rays; ++i) {
      uint32_t x = uint32_t(i) * 0x9E3779B1u ^ uint32_t(j) * 0x85EBCA77u;
      x ^= x >> 15, x *= 0x2C1B3C6Du, x ^= x >> 12;
      const double jx = (x & 0xFFFF) / 65536.0, jy = (x >> 16) / 65536.0;
      view.entries.push_back({(i + jx) / rays, (j + jy) / rays});
      view.exact.push_back(reference::parallax_hit(height, view.entries.back(), d, base.depth));
    }
  return view;
}

// Every ray of the view through one tracer (W × H texels); the mean time per ray into
// *ns_per_ray (a pass of its own, without counting), the operations of all into *ops.
std::vector<modules::ParallaxTrace> trace_rays(const Method& method, const modules::ParallaxMaps& maps,
                                               const View& view, double W, double H, double* ns_per_ray,
                                               modules::Ops* ops) {
  const auto& entries = view.entries;
  const glm::dvec3& d = view.direction;
  std::vector<modules::ParallaxTrace> traces(entries.size());
  auto trace = [&](size_t r, modules::Ops* counted) {
    return modules::trace_parallax(method.s, maps, float(entries[r].x * W - 0.5), float((1 - entries[r].y) * H - 0.5),
                                   float(d.x), float(d.y), float(d.z), counted);
  };
  const auto start = std::chrono::steady_clock::now();
  for (size_t r = 0; r < entries.size(); ++r) traces[r] = trace(r, nullptr);
  *ns_per_ray = seconds_since(start) * 1e9 / double(entries.size());
  for (size_t r = 0; r < entries.size(); ++r) trace(r, ops);
  return traces;
}

// One tracer's results on a view, ray by ray and summed, against the exact hits.
struct RayFigures {
  std::vector<int> iterations;
  std::vector<double> cycles;  // parallax_cycles
  std::vector<double> error;   // uv error, texels
  double fetches = 0, overshoot = 0, skips = 0, cells = 0;
  size_t more_than_box_gap = 0;
  size_t wrong_layer = 0, past_hit = 0;
};

// Compares the traces with the exact hits (W × H texels); `refined` counts the rays that
// took more iterations than the box-gap map did on the same ray (box_gap_iterations).
RayFigures compare_with_exact(const std::vector<modules::ParallaxTrace>& traces, const View& view, double W,
                              double H, int64_t cell_cycles, bool refined, const std::vector<int>& box_gap_iterations) {
  const auto& entries = view.entries;
  const auto& exact = view.exact;
  const glm::dvec3& d = view.direction;
  RayFigures results;
  results.iterations.resize(entries.size());
  results.cycles.resize(entries.size());
  results.error.resize(entries.size());
  for (size_t r = 0; r < entries.size(); ++r) {
    const auto& t = traces[r];
    // Back to uv, and the error in texels against the exact hit (wrapped).
    const double u = (t.x + 0.5) / W, v = 1 - (t.y + 0.5) / H;
    double eu = (u - exact[r].uv.x) * W, ev = (v - exact[r].uv.y) * H;
    eu -= W * std::round(eu / W), ev -= H * std::round(ev / H);
    results.error[r] = std::sqrt(eu * eu + ev * ev);
    results.iterations[r] = t.iterations;
    results.cycles[r] = double(modules::parallax_cycles(t, cell_cycles));
    results.fetches += t.fetches;
    results.skips += t.skips;
    results.cells += t.cells;
    if (refined && t.iterations > box_gap_iterations[r]) ++results.more_than_box_gap;
    // Where along the ray the result lies (its projection), against the hit.
    const double du = (u - entries[r].x) * W, dv = (v - entries[r].y) * H;
    const double along = (du * d.x * W + dv * d.y * H) / (d.x * W * d.x * W + d.y * H * d.y * H + 1e-300);
    const double past = (along - exact[r].t) * view.tracer_length;  // voxels past the exact hit
    results.overshoot = std::max(results.overshoot, past);
    if (past > 1e-3) ++results.past_hit;
    if ((along - exact[r].t_exit) * view.tracer_length > 0.01) ++results.wrong_layer;  // 0.01 voxel: rounding
  }
  return results;
}

// The value below which a share p of v lies (p = 1: the largest; 0 when v is empty).
double percentile(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[std::min(v.size() - 1, size_t(p * double(v.size())))];
}

// Mean, 95th percentile and maximum of v.
nlohmann::json spread(const std::vector<double>& v) {
  double sum = 0;
  for (double x : v) sum += x;
  return {{"mean", v.empty() ? 0.0 : sum / double(v.size())}, {"p95", percentile(v, 0.95)}, {"max", percentile(v, 1.0)}};
}

// One tracer's figures on a view, as written: means, 95th percentiles and maxima per ray;
// operations per ray (arithmetic: every kind but fetches).
nlohmann::json method_figures(const RayFigures& results, const modules::Ops& ops, double ns_per_ray) {
  std::vector<double> it(results.iterations.begin(), results.iterations.end());
  double err_sum = 0;
  for (double x : results.error) err_sum += x;
  const double n = double(results.iterations.size());
  const double arithmetic = double(ops.total() - ops.fetch);
  return {{"iterations", spread(it)},
          {"cycles", spread(results.cycles)},
          {"ops", arithmetic / n},
          {"ops_by_kind", {{"add", double(ops.add) / n}, {"mul", double(ops.mul) / n}, {"div", double(ops.div) / n},
                           {"sqrt", double(ops.sqrt + ops.rsqrt) / n}}},
          {"fetches", results.fetches / n},
          {"skips", results.skips / n},
          {"cells", results.cells / n},
          {"uv_error_texels",
           {{"mean", err_sum / n}, {"p95", percentile(results.error, 0.95)}, {"max", percentile(results.error, 1.0)}}},
          {"wrong_layer", double(results.wrong_layer) / n},
          {"past_hit", double(results.past_hit) / n},
          {"max_overshoot_voxels", results.overshoot},
          {"ns_per_ray", ns_per_ray}};
}

// Runs one tracer on every ray of a view and returns its figures; the box-gap map's
// iterations are kept (box_gap_iterations, per ray) for the refined map's per-ray gate.
nlohmann::json measure_method(const Method& method, const modules::ParallaxMaps& maps, const View& view,
                              const core::Texture& height, int64_t cell_cycles, std::vector<int>& box_gap_iterations) {
  const double W = height.width, H = height.height;
  double ns = 0;
  modules::Ops ops;
  const std::vector<modules::ParallaxTrace> traces = trace_rays(method, maps, view, W, H, &ns, &ops);
  const bool refined = method.name.rfind("refined", 0) == 0;
  const RayFigures results = compare_with_exact(traces, view, W, H, cell_cycles, refined, box_gap_iterations);
  nlohmann::json figures = method_figures(results, ops, ns);
  if (method.name == "box-gap") box_gap_iterations = results.iterations;
  if (refined) figures["rays_over_box_gap"] = results.more_than_box_gap;
  return figures;
}

// Writes the figures as JSON to `path` (nothing when it is empty).
void write_figures(const std::string& path, const nlohmann::json& out) {
  if (path.empty()) return;
  core::write_file(path, out.dump(2) + "\n");
}

// A short table on the terminal: iterations and error per method and view.
void print_table(const nlohmann::json& views) {
  for (const auto& view : views) {
    std::cout << "elevation " << view["elevation_deg"].get<double>() << "° (tracer "
              << view["tracer_elevation_deg"].get<double>() << "°)\n";
    for (const auto& [name, m] : view["methods"].items())
      std::cout << "  " << name << ": iterations " << m["iterations"]["mean"].get<double>() << " / "
                << m["iterations"]["p95"].get<double>() << " / " << m["iterations"]["max"].get<double>()
                << " (skips " << m["skips"].get<double>() << ")"
                << ", uv error " << m["uv_error_texels"]["mean"].get<double>() << " / "
                << m["uv_error_texels"]["p95"].get<double>() << " / " << m["uv_error_texels"]["max"].get<double>()
                << " texels, wrong layer " << m["wrong_layer"].get<double>() << ", overshoot "
                << m["max_overshoot_voxels"].get<double>() << " voxels, " << m["ns_per_ray"].get<double>() << " ns"
                << ", " << m["cycles"]["mean"].get<double>() << " cycles, " << m["ops"].get<double>() << " ops"
                << (m.contains("rays_over_box_gap") ? ", rays over box-gap " + m["rays_over_box_gap"].dump() : "")
                << "\n";
  }
}

}  // namespace

Command add_parallax_bench_command(CLI::App& app) {
  auto opt = std::make_shared<BenchOptions>();
  CLI::App* cmd = app.add_subcommand(
      "parallax-bench", "every parallax tracer against the exact hit, on parallel rays over a material's height map");
  opt->scene.add_to(*cmd);
  cmd->add_option("--material", opt->material, "the parallax material (default: the first)")
      ->check(kNotEmpty);
  cmd->add_option("--elevations", opt->elevations, "view elevations above the surface, degrees")
      ->delimiter(',')
      ->capture_default_str()
      ->check(finite_in(0.5, 89.0));  // the along-ray measures project on the sideways direction
  cmd->add_option("--margins", opt->margins,
                  "refined maps to measure, one per margin in voxels (default: the material's margin)")
      ->delimiter(',')
      ->check(finite_in(0.0, 64.0));
  cmd->add_option("--azimuth", opt->azimuth, "view azimuth from the u axis, degrees")
      ->capture_default_str()
      ->check(finite_in(-360, 360));
  cmd->add_option("--rays", opt->rays, "rays per side (a jittered grid over the map)")
      ->capture_default_str()
      ->check(finite_in(1, 4096));
  cmd->add_option("--json", opt->json, "write the figures as JSON")
      ->check(kNotEmpty);
  return {cmd, [opt]() {
            const core::Scene scene = opt->scene.load();
            check_outputs({{"--json", opt->json}}, scene.inputs);
            const core::Material& mat = parallax_material(scene, opt->material);
            const core::Texture& height = scene.textures[size_t(mat.height_map)];
            const core::ParallaxSettings base = mat.parallax;
            const std::vector<Method> methods = methods_to_compare(base, opt->margins);
            nlohmann::json out = bench_header(*opt, scene, mat, height);
            const int64_t cell_cycles = modules::parallax_cell_cycles(core::read<modules::PipelineSettings>(settings_of(scene), "").unit);
            out["cell_cycles"] = cell_cycles;
            const std::vector<modules::ParallaxMaps> maps = build_maps(methods, height, scene.file, out);
            std::vector<int> box_gap_iterations;  // per ray, for the refined map's per-ray gate
            for (double elevation : opt->elevations) {
              const View view = view_at(elevation, opt->azimuth, opt->rays, height, base);
              nlohmann::json figures = {{"elevation_deg", elevation},
                                        {"tracer_elevation_deg", view.tracer_elevation_deg}};
              for (size_t k = 0; k < methods.size(); ++k)
                figures["methods"][methods[k].name] =
                    measure_method(methods[k], maps[k], view, height, cell_cycles, box_gap_iterations);
              out["views"].push_back(figures);
            }
            write_figures(opt->json, out);
            print_table(out["views"]);
            return 0;
          }};
}

}  // namespace shadetlm::app
