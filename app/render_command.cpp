// shadetlm render [SCENE] [-o frame.exr] [--preview frame.png] [--stats stats.json]
//                 [--compare-reference] [--engine systemc|loop] [--set key=value ...]
#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>

#include "app/commands.hpp"
#include "core/compare.hpp"
#include "modules/pipeline/pipeline.hpp"
#include "reference/reference.hpp"

namespace app {

namespace {
// Error of the pipeline's frame against the golden model's, per layer, and the
// pixels whose coverage differs.
nlohmann::json error_against_reference(const core::Frame& frame, const core::Scene& scene, double* reference_s) {
  const auto start = std::chrono::steady_clock::now();
  const core::Frame ref = reference::to_frame(reference::render(scene));
  *reference_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  core::CompareOptions o;
  o.fail = 0;  // report, do not judge
  const core::CompareResult r = core::compare_frames(frame, ref, o);
  nlohmann::json j;
  for (const auto& m : r.layers) {
    const std::string key = m.layer == "RGB" ? "rgb" : m.layer == "Z" ? "z" : "n";
    j[key] = {{"max", std::isfinite(m.max_abs) ? nlohmann::json(m.max_abs) : nlohmann::json("inf")},
              {"max_at", {m.max_x, m.max_y}},
              {"rmse", std::isfinite(m.rmse) ? nlohmann::json(m.rmse) : nlohmann::json("inf")},
              {"psnr", std::isfinite(m.psnr) ? nlohmann::json(m.psnr) : nlohmann::json("inf")}};
  }
  size_t coverage = 0;
  const auto &a = frame.at("A"), &b = ref.at("A");
  for (size_t i = 0; i < a.size(); ++i) coverage += a[i] != b[i];
  j["coverage_mismatches"] = coverage;
  return j;
}
}  // namespace

Command add_render_command(CLI::App& app) {
  struct Options {
    SceneOptions scene;
    std::string output = "out/frame.exr", preview, stats, engine = "systemc";
    bool compare = false;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("render", "render a scene through the SystemC/TLM-2.0 pipeline");
  opt->scene.add_to(*cmd);
  cmd->add_option("-o,--output", opt->output, "EXR frame to write")->capture_default_str();
  cmd->add_option("--preview", opt->preview, "also write an sRGB PNG preview");
  cmd->add_option("--stats", opt->stats, "write statistics (time, cycles, operations, error) as JSON");
  cmd->add_flag("--compare-reference", opt->compare, "also render the golden model and report the error");
  cmd->add_option("--engine", opt->engine,
                  "systemc: the TLM-2.0 model; loop: the same kernels in a plain C++ loop (no timing)")
      ->check(CLI::IsMember({"systemc", "loop"}))
      ->capture_default_str();
  return {cmd, [opt]() {
            const core::Scene scene = opt->scene.load();
            modules::RenderResult r =
                opt->engine == "loop" ? modules::render_loop(scene) : modules::render_systemc(scene);
            nlohmann::json stats = r.stats_json();
            stats["scene"] = scene.file;
            stats["config"] = scene.pipeline.resolved();
            double reference_s = 0;
            if (opt->compare) stats["error"] = error_against_reference(r.frame, scene, &reference_s);
            describe(r.frame, scene, opt->scene, opt->engine == "loop" ? "pipeline-loop" : "pipeline");
            // Frame, preview and statistics appear together or not at all: the
            // statistics go to a temporary first and are renamed after the frame.
            const std::string stats_tmp = opt->stats.empty() ? "" : core::temporary_path_for(opt->stats);
            try {
              if (!stats_tmp.empty()) {
                std::ofstream out(stats_tmp);
                out << stats.dump(2) << "\n";
                if (!out) throw std::runtime_error(opt->stats + ": cannot write the statistics");
              }
              write_frame(r.frame, opt->output, opt->preview);
            } catch (...) {
              if (!stats_tmp.empty()) core::remove_quietly(stats_tmp);
              throw;
            }
            if (!stats_tmp.empty()) {
              try {
                core::rename_into_place(stats_tmp, opt->stats);
              } catch (...) {  // take the frame back: no output of a run that failed
                core::remove_quietly(opt->output);
                if (!opt->preview.empty()) core::remove_quietly(opt->preview);
                throw;
              }
            }
            std::cout << "render (" << r.engine << "): " << scene.file << ", " << scene.camera.width << "x"
                      << scene.camera.height << ", " << r.triangles_drawn << " triangles, " << r.pixels_shaded
                      << " shaded pixels, " << r.wall_s << " s\n";
            if (r.frame_cycles > 0)
              std::cout << "  " << r.frame_cycles << " cycles at " << r.clock_mhz << " MHz ("
                        << stats["sim_time_s"].get<double>() * 1e3 << " ms simulated), bottleneck "
                        << stats["bottleneck"].get<std::string>() << "\n";
            if (opt->compare) {
              const auto& e = stats["error"];
              for (const char* layer : {"rgb", "z", "n"})
                if (e.contains(layer))
                  std::cout << "  error " << layer << ": max " << e[layer]["max"] << " at ("
                            << e[layer]["max_at"][0] << ", " << e[layer]["max_at"][1] << "), rmse "
                            << e[layer]["rmse"] << ", psnr " << e[layer]["psnr"] << " dB\n";
              std::cout << "  coverage mismatches: " << e["coverage_mismatches"] << " (golden model: "
                        << reference_s << " s)\n";
            }
            std::cout << "  wrote " << opt->output << (opt->preview.empty() ? "" : " and " + opt->preview)
                      << (opt->stats.empty() ? "" : " and " + opt->stats) << "\n";
            return 0;
          }};
}

}  // namespace app
