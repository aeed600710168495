// shadetlm bench [SCENE] [--set key=value ...]: the SystemC pipeline against the same
// kernels in a plain loop, measured in one run (these machines are noisy): a warm-up
// loop (discarded: first touches of memory), loop, SystemC, loop; the ratio is
// SystemC's time over the two loops' mean. One SystemC run a process: SystemC cannot
// elaborate a second pipeline once a simulation has run (E529), so scripts/bench.sh
// takes the median of several processes. Then the other phases of a render of the scene:
// loading it, the golden model on --threads threads, and encoding the SystemC frame as
// EXR (--compression, on OpenEXR's pool of --threads).
#include <chrono>
#include <filesystem>
#include <iostream>

#include "app/commands.hpp"
#include "shadetlm/core/compare.hpp"
#include "shadetlm/modules/pipeline/pipeline.hpp"
#include "shadetlm/reference/reference.hpp"

namespace shadetlm::app {

Command add_bench_command(CLI::App& app) {
  auto opt = std::make_shared<SceneOptions>();
  CLI::App* cmd = app.add_subcommand("bench", "time the SystemC pipeline against the plain kernel loop");
  opt->add_to(*cmd);
  return {cmd, [opt]() {
            using clock = std::chrono::steady_clock;
            const auto seconds_since = [](clock::time_point t) { return std::chrono::duration<double>(clock::now() - t).count(); };
            auto start = clock::now();
            const core::Scene scene = opt->load();
            const double load_s = seconds_since(start);
            take_run_memory(scene, true, false, 0);
            modules::render_loop(scene);  // warm-up
            const modules::RenderResult first = modules::render_loop(scene);
            const modules::RenderResult systemc = modules::render_systemc(scene);
            const modules::RenderResult second = modules::render_loop(scene);
            const double loop_s = (first.wall_s + second.wall_s) / 2;
            take_run_memory(scene, false, true, 0);
            start = clock::now();
            reference::render(scene, threads());
            const double golden_s = seconds_since(start);
            // The frame written as render writes it, to a temporary of a file that never appears.
            const std::string scratch = (std::filesystem::temp_directory_path() / "shadetlm-bench.exr").string();
            start = clock::now();
            uint64_t bytes = 0;
            {
              core::OutputSet outputs;  // (not committed: its temporary goes with it)
              outputs.write_with(scratch, [&](const std::string& tmp) {
                core::write_exr_to(tmp, scratch, systemc.frame);
                bytes = std::filesystem::file_size(tmp);
              });
            }
            const double write_s = seconds_since(start);
            const double pixels = double(systemc.pixels_shaded);
            std::cout << "bench: " << scene.file << ", " << scene.camera.width << "x" << scene.camera.height
                      << ", " << systemc.pixels_shaded << " shaded pixels\n"
                      << "  loop:    " << first.wall_s << " s, " << second.wall_s << " s  ("
                      << loop_s / pixels * 1e9 << " ns per shaded pixel)\n"
                      << "  systemc: " << systemc.wall_s << " s  (" << systemc.wall_s / pixels * 1e9
                      << " ns per shaded pixel)\n"
                      << "  ratio systemc / loop: " << systemc.wall_s / loop_s << "\n"
                      << "  phases of a render: load " << core::figure(load_s) << " s, pipeline (systemc) "
                      << core::figure(systemc.wall_s) << " s, golden model " << core::figure(golden_s) << " s, write "
                      << core::figure(write_s) << " s (encoding " << bytes << " bytes of EXR), on " << threads()
                      << " threads\n";
            return 0;
          }};
}

}  // namespace shadetlm::app
