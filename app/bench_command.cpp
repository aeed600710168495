// shadetlm bench [SCENE] [--set key=value ...]: the SystemC pipeline against the same
// kernels in a plain loop, measured in one run (these machines are noisy): a warm-up
// loop (discarded: first touches of memory), loop, SystemC, loop; the ratio is
// SystemC's time over the two loops' mean. One SystemC run a process: SystemC cannot
// elaborate a second pipeline once a simulation has run (E529), so scripts/bench.sh
// takes the median of several processes.
#include <iostream>

#include "app/commands.hpp"
#include "shadetlm/modules/pipeline/pipeline.hpp"

namespace shadetlm::app {

Command add_bench_command(CLI::App& app) {
  auto opt = std::make_shared<SceneOptions>();
  CLI::App* cmd = app.add_subcommand("bench", "time the SystemC pipeline against the plain kernel loop");
  opt->add_to(*cmd);
  return {cmd, [opt]() {
            const core::Scene scene = opt->load();
            take_run_memory(scene, true, false, 0);
            modules::render_loop(scene);  // warm-up
            const modules::RenderResult first = modules::render_loop(scene);
            const modules::RenderResult systemc = modules::render_systemc(scene);
            const modules::RenderResult second = modules::render_loop(scene);
            const double loop_s = (first.wall_s + second.wall_s) / 2;
            const double pixels = double(systemc.pixels_shaded);
            std::cout << "bench: " << scene.file << ", " << scene.camera.width << "x" << scene.camera.height
                      << ", " << systemc.pixels_shaded << " shaded pixels\n"
                      << "  loop:    " << first.wall_s << " s, " << second.wall_s << " s  ("
                      << loop_s / pixels * 1e9 << " ns per shaded pixel)\n"
                      << "  systemc: " << systemc.wall_s << " s  (" << systemc.wall_s / pixels * 1e9
                      << " ns per shaded pixel)\n"
                      << "  ratio systemc / loop: " << systemc.wall_s / loop_s << "\n";
            return 0;
          }};
}

}  // namespace shadetlm::app
