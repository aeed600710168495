// shadetlm timing-check LOG: runs the clocked timing reference (timing_reference/) on
// the work recorded in a timing log (`shadetlm render --timing-log LOG`) and compares
// every pixel's start and hand-over at every block, each triangle's times, the pass's
// end and the blocks' busy, starved and blocked cycles and FIFO figures with the fast
// model's. Exit 0: all equal; 1: some differ.
#include <iostream>

#include "app/commands.hpp"
#include "shadetlm/timing_reference/clocked.hpp"

namespace shadetlm::app {

Command add_timing_check_command(CLI::App& app) {
  auto log = std::make_shared<std::string>();
  auto show = std::make_shared<size_t>(10);
  CLI::App* cmd = app.add_subcommand(
      "timing-check", "check a render's timing log against the clocked timing reference; exit 0 equal, 1 not");
  cmd->add_option("log", *log, "timing log written by `shadetlm render --timing-log`")->required();
  cmd->add_option("--show", *show, "differences described")->capture_default_str()->check(finite_in(0, 1000000));
  return {cmd, [log, show]() {
            const timing_reference::Workload w = timing_reference::read_workload(*log);
            const timing_reference::Measured m = timing_reference::run_clocked(w);
            std::string report;
            const bool equal = timing_reference::compare(w, m, report, *show);
            std::cout << *log << ": " << report << "  clocked reference: " << m.end << " cycles stepped in "
                      << m.wall_s << " s\n"
                      << (equal ? "EQUAL" : "DIFFERENT") << "\n";
            return equal ? 0 : 1;
          }};
}

}  // namespace shadetlm::app
