// shadetlm timing-check LOG: runs the clocked timing reference (timing_reference/) on
// the work recorded in a timing log (`shadetlm render --timing-log LOG`) and compares
// every pixel's start and hand-over at every block, each triangle's times, the passes'
// ends and the blocks' busy, starved and blocked cycles and FIFO figures with the fast
// model's. The triangles setup hands on and drops and each one's walk come from the
// scene the log names (or --scene and --set), not from the log, which is held to them.
// Exit 0: all equal; 1: some differ.
//
// --rtl-normalize MODE puts the RTL normalize unit of that mode (docs/rtl.md) in place
// of the reference's own unit for the normalize block, in lockstep with its clock;
// --rtl-vcd FILE traces its pins and registers.
#include <algorithm>
#include <iostream>

#include "app/commands.hpp"
#include "shadetlm/core/input_error.hpp"
#include "shadetlm/core/output.hpp"
#include "shadetlm/modules/normalize/normalize_kernel.hpp"
#include "shadetlm/timing_reference/clocked.hpp"
#include "shadetlm/timing_reference/scene_walk.hpp"
#ifdef SHADETLM_HAVE_RTL
#include "shadetlm/rtl/normalize/normalize_unit_pins.hpp"
#endif

namespace shadetlm::app {

#ifdef SHADETLM_HAVE_RTL
namespace {
// The log can be checked with the RTL unit of `mode`: it has a normalize block of the
// unit's timing, and (forward-difference, which seeds at a packet's first pixel) k records.
void check_rtl_log(const timing_reference::Workload& w, const std::string& log, const std::string& mode,
                   rtl::UnitTiming unit) {
  const auto block = std::find_if(w.blocks.begin(), w.blocks.end(), [](const auto& b) { return b.name == "normalize"; });
  if (block == w.blocks.end()) throw core::InputError(log, "block", "the log has no normalize block for --rtl-normalize");
  if (block->latency != unit.latency || block->ii != unit.ii)
    throw core::InputError(log, "block normalize",
                           "latency " + std::to_string(block->latency) + ", II " + std::to_string(block->ii) +
                               "; the RTL unit of mode " + mode + " has latency " + std::to_string(unit.latency) +
                               ", II " + std::to_string(unit.ii) + " (render with pipeline.normalize.mode=" + mode +
                               " and the default units)");
  if (mode == "forward-difference" && !w.pixels.empty() &&
      std::none_of(w.pixels.begin(), w.pixels.end(), [](const auto& p) { return p.first; }))
    throw core::InputError(log, "k", "no k records (where packets start): a log of an older build? render again");
}
}  // namespace
#endif

namespace {
// The scene's walk (timing_reference/scene_walk.hpp) in the log's place: the scene
// `scene` with `sets`, or else the log's scene and set records. Returns the differences
// between the log and the scene, described ("" if none).
std::string walk_from_scene(timing_reference::Workload& w, const std::string& log, const std::string& scene,
                            const std::vector<std::string>& sets, size_t show) {
  SceneOptions options;
  options.scene = scene.empty() ? w.scene : scene;
  options.given = !scene.empty();
  options.overrides = scene.empty() && sets.empty() ? w.sets : sets;
  if (scene.empty() && !w.scene_given)
    throw core::InputError(log, "scene", "no scene record (a log of an older build?): give --scene and --set");
  const core::Scene s = options.load();
  w.reject_cycles = settings_of(s).integer("setup.reject_cycles");
  std::string report;
  const size_t differences = timing_reference::apply_walk(timing_reference::derive_walks(s), w, report, show);
  if (timing_reference::serial_cycles(w) > 1e11)
    throw core::InputError(log, "", "more than 10^11 cycles to step: too long to check");
  if (differences == 0) return "";
  return "  " + std::to_string(differences) + " differences between the log and the scene's walk\n" + report;
}
}  // namespace

Command add_timing_check_command(CLI::App& app) {
  auto log = std::make_shared<std::string>();
  auto show = std::make_shared<size_t>(10);
  auto rtl_mode = std::make_shared<std::string>();
  auto rtl_vcd = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "timing-check", "check a render's timing log against the clocked timing reference; exit 0 equal, 1 not");
  cmd->add_option("log", *log, "timing log written by `shadetlm render --timing-log`")->required();
  cmd->add_option("--show", *show, "differences described")->capture_default_str()->check(finite_in(0, 1000000));
  cmd->add_option("--rtl-normalize", *rtl_mode, "the RTL normalize unit of this mode as the normalize block's unit")
      ->check(CLI::IsMember(modules::normalize_mode_names()));
  cmd->add_option("--rtl-vcd", *rtl_vcd, "trace the RTL unit's pins and registers to this VCD file")
      ->needs("--rtl-normalize");
  auto scene = std::make_shared<std::string>();
  auto sets = std::make_shared<std::vector<std::string>>();
  cmd->add_option("--scene", *scene, "the scene the log was rendered from (default: the log's scene record)");
  cmd->add_option("--set", *sets, "the render's overrides, key=value (default: the log's set records)")
      ->take_all()
      ->allow_extra_args(false);
  return {cmd, [log, show, rtl_mode, rtl_vcd, scene, sets]() {
            timing_reference::Workload w = timing_reference::read_workload(*log);
            std::unique_ptr<core::Temporary> vcd;  // the trace, renamed into place once whole
            std::unique_ptr<timing_reference::UnitPins> pins;
            if (!rtl_mode->empty()) {
#ifdef SHADETLM_HAVE_RTL
              if (!rtl_vcd->empty()) {
                if (rtl_vcd->size() < 5 || rtl_vcd->substr(rtl_vcd->size() - 4) != ".vcd")
                  throw core::InputError("--rtl-vcd", *rtl_vcd, "the waveform file must end in .vcd");
                check_outputs({{"--rtl-vcd", *rtl_vcd}}, {*log});
                vcd = std::make_unique<core::Temporary>(*rtl_vcd);
              }
              const int mode = int(modules::parse_normalize_mode(*rtl_mode));
              check_rtl_log(w, *log, *rtl_mode, rtl::normalize_unit_timing(mode));
              pins = rtl::make_normalize_unit_pins(mode, vcd ? vcd->path() : std::string());
#else
              throw core::InputError("--rtl-normalize", *rtl_mode,
                                     "this build has no RTL (built without Verilator, or with SHADETLM_RTL=OFF)");
#endif
            }
            // (After the RTL's checks of the log as written: its packet starts, its units.)
            const std::string walk_report = walk_from_scene(w, *log, *scene, *sets, *show);
            const timing_reference::Measured m = timing_reference::run_clocked(w, "normalize", pins.get());
            pins.reset();  // (closes the trace)
            if (vcd) vcd->commit();
            std::string report;
            const bool equal = timing_reference::compare(w, m, report, *show) && walk_report.empty();
            std::cout << *log << ": " << report << walk_report << "  clocked reference: " << m.end
                      << " cycles stepped in " << m.wall_s << " s\n"
                      << (equal ? "EQUAL" : "DIFFERENT") << "\n";
            return equal ? 0 : 1;
          }};
}

}  // namespace shadetlm::app
