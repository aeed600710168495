// shadetlm reference [SCENE] -o ref.exr [--preview ref.png] [--set key=value ...]
#include <chrono>
#include <iostream>

#include "app/commands.hpp"
#include "app/progress.hpp"
#include "shadetlm/core/compare.hpp"
#include "shadetlm/reference/reference.hpp"

namespace shadetlm::app {

Command add_reference_command(CLI::App& app) {
  struct Options {
    SceneOptions scene;
    std::string output = "out/reference.exr", preview;
    bool allow_nonfinite = false;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("reference", "render a scene through the golden model (exact, double precision)");
  opt->scene.add_to(*cmd);
  cmd->add_option("-o,--output", opt->output, "EXR frame to write")->capture_default_str()
      ->check(kNotEmpty)
      ->check(kExrPath);
  cmd->add_option("--preview", opt->preview, "also write an sRGB PNG preview (FILE.png)")
      ->check(kNotEmpty)
      ->check(kPngPath);
  cmd->add_flag("--allow-nonfinite", opt->allow_nonfinite,
                "exit 0 even when NaN or infinite values reached the frame (written as 0; else exit status 3)");
  return {cmd, [opt]() {
            Progress progress("reference");
            progress.phase("loading the scene");
            const core::Scene scene = opt->scene.load();
            require_output("--output", opt->output);
            check_outputs({{"--output", opt->output}, {"--preview", opt->preview}}, scene.inputs);
            take_run_memory(scene, false, true, 0);
            progress.phase("golden model");
            const auto start = std::chrono::steady_clock::now();
            const reference::Image image = reference::render(scene, threads());
            const double seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            core::Frame frame = reference::to_frame(image, threads());
            const uint64_t replaced = replace_nonfinite(frame);
            describe(frame, scene, opt->scene, "reference");
            progress.phase("writing");
            write_frame(frame, opt->output, opt->preview);
            progress.done();
            size_t covered = 0;
            for (double a : image.alpha) covered += a > 0;
            std::cout << "reference: " << scene.file << ", " << image.width << "x" << image.height
                      << ", " << covered << " pixels covered, " << core::figure(seconds) << " s\n"
                      << "  wrote " << opt->output << (opt->preview.empty() ? "" : " and " + opt->preview)
                      << "\n";
            return nonfinite_status(replaced, opt->allow_nonfinite);
          }};
}

}  // namespace shadetlm::app
