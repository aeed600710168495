// shadetlm: the SystemC/TLM-2.0 shading-pipeline model and its tools.
#include <cstdlib>
#include <iostream>

#include <systemc>

#include "app/commands.hpp"
#include "shadetlm/core/input_error.hpp"
#include "shadetlm/core/memory_budget.hpp"
#include "shadetlm/core/output.hpp"
#include "shadetlm/core/version.hpp"
#include "shadetlm/modules/normalize/normalize_rtl.hpp"

using namespace shadetlm;  // core::, modules::, reference::

// libsystemc calls sc_main from its own main(); shadetlm has its own main and
// starts the simulation itself (modules::render_systemc), so this is never run.
extern "C" int sc_main(int, char**) { return 1; }

// SystemC's own handler displays reports on stdout, where the results go: shown on
// stderr instead, the rest (throw, stop) left to it.
void report_to_stderr(const sc_core::sc_report& report, const sc_core::sc_actions& actions) {
  if (actions & sc_core::SC_DISPLAY) std::cerr << sc_core::sc_report_compose_message(report) << "\n";
  sc_core::sc_report_handler::default_handler(report, actions & ~sc_core::SC_DISPLAY);
}

int main(int argc, char** argv) {
  setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 1);  // keep stdout for results
  core::remove_temporaries_on_signals();  // an interrupted run leaves no partial output
  // SystemC errors become exceptions (reported with exit code 1), warnings go to stderr.
  sc_core::sc_report_handler::set_actions(sc_core::SC_ERROR, sc_core::SC_THROW);
  sc_core::sc_report_handler::set_actions(sc_core::SC_WARNING, sc_core::SC_DISPLAY);
  sc_core::sc_report_handler::set_actions(sc_core::SC_INFO, sc_core::SC_DO_NOTHING);  // e.g. the VCD timescale
  sc_core::sc_report_handler::set_handler(report_to_stderr);
  CLI::App app{"shadetlm: a SystemC/TLM-2.0 model of a per-pixel shading pipeline"};
  // The version, and what RTL this build has (docs/rtl.md).
  app.set_version_flag("-V,--version", [] { return std::string(core::kVersion) + "\nrtl: " + modules::normalize_rtl_build(); });
  app.require_subcommand(1);
  app.footer(
      "Examples:\n"
      "  shadetlm render -o demo.exr                           the built-in demo\n"
      "  shadetlm render scenes/bench-1080p.json -o f.exr --stats stats.json\n"
      "  shadetlm render golden/sphere/scene.json -o f.exr --set pipeline.normalize.mode=exact\n"
      "  shadetlm compare a.exr b.exr                          exit 0 if they match, as idiff\n"
      "  shadetlm render --help                                a command's own options\n"
      "Docs: README.md (start there), docs/cli.md, docs/configuration.md\n");
  std::string max_memory;
  app.add_option("--max-memory", max_memory,
                 "memory a run may take, e.g. 8G or 512M (default: half the machine's); given before or after the "
                 "subcommand");
  std::string threads, compression = "zip";
  app.add_option("--threads", threads,
                 "threads for the golden model and for compressing EXR files (default: one per core); the SystemC "
                 "pipeline runs on one")
      ->check(app::kNotEmpty);
  app.add_option("--compression", compression,
                 "how EXR files are compressed: none, rle, zips, zip (default) or piz, OpenEXR's lossless methods "
                 "(docs/performance.md)")
      ->check(app::kNotEmpty);
  app.fallthrough();  // (so that `render --max-memory 8G` reaches it)
  std::vector<app::Command> commands = {app::add_render_command(app), app::add_reference_command(app),
                                        app::add_compare_command(app), app::add_bench_command(app),
                                        app::add_precompute_command(app), app::add_parallax_bench_command(app),
                                        app::add_timing_check_command(app), app::add_cost_command(app)};
  app::tidy_help(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // Arguments left over, or no subcommand: perhaps a typo of one it has.
    const bool typo = dynamic_cast<const CLI::ExtrasError*>(&e) || dynamic_cast<const CLI::RequiredError*>(&e);
    if (typo)
      if (const std::string hint = app::suggestion(app, argc, argv); !hint.empty()) {
        std::cerr << "shadetlm: " << hint << "\n";
        return 2;
      }
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    // Said by the command it is about, like every other message (not CLI11's bare line).
    std::string where = "shadetlm";
    for (const CLI::App* sub = &app; !sub->get_subcommands().empty();) {
      sub = sub->get_subcommands().front();
      where += " " + sub->get_name();
    }
    std::cerr << where << ": " << core::printable(e.what(), 300) << " (" << where << " --help shows its arguments)\n";
    return 2;
  }
  try {
    if (!max_memory.empty()) core::MemoryBudget::process().set_limit(core::parse_bytes(max_memory, "--max-memory"));
    app::set_threads(threads);
    app::set_compression(compression);
    for (const auto& command : commands)
      if (command.cli->parsed()) return command.run();
  } catch (const core::InputError& e) {
    std::cerr << "shadetlm: " << e.what() << "\n";
    return 2;
  } catch (const std::bad_alloc&) {
    std::cerr << "shadetlm: out of memory: an allocation failed below the run's --max-memory budget (a limit such as "
                 "ulimit -v, or the machine's memory in use elsewhere)\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "shadetlm: " << e.what() << "\n";
    return 1;
  } catch (...) {
    std::cerr << "shadetlm: an unknown error\n";
    return 1;
  }
  return 1;
}
