// The golden scenes (golden/<scene>/), each in a test case of its own (one SystemC
// simulation per process). golden/<scene>/golden.json says what each checks and with
// which thresholds, each with its reason (docs/regression.md); scripts/regress.sh reads
// the same file for its report. Per scene:
//
//  1. equivalence — the SystemC pipeline and the same kernels in a plain loop give
//     bit-identical frames: the transaction-level wrapping changes nothing;
//  2. accuracy — against the golden model: every pixel's colour within `rgb_max`, or a
//     PSNR of at least `rgb_min_psnr` for paths that approximate by design; coverage
//     identical;
//  3. regression — the frame matches the accepted golden/<scene>/frame.exr per layer
//     (colour, depth, normals), and the simulated cycles the accepted stats.json;
//  4. each further configuration (`configurations`: `--set` overrides) through the
//     loop: accuracy and regression against frame.<name>.exr.
// REGEN_GOLDEN=1 rewrites a frame (and stats) that is missing or fails, and says what
// changed; never under CI.
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>

#include "shadetlm/core/compare.hpp"
#include "shadetlm/modules/pipeline/pipeline.hpp"
#include "shadetlm/reference/reference.hpp"
#include "systemc_harness.hpp"
#include "test_util.hpp"

using namespace shadetlm;  // core::, modules::, reference::

namespace {

using nlohmann::json;

bool regenerate() {
  const char* regen = std::getenv("REGEN_GOLDEN");
  return regen && std::string(regen) == "1" && !std::getenv("CI");
}

// The figures of the frame's timing that regression compares.
// What scripts/regress.py accepts too: the frame's cycles, each block's busy cycles and
// the cycle it handed on its last result (where a latency shows that busy cycles hide).
json cycle_stats(const modules::RenderResult& r) {
  json j = {{"frame_cycles", r.frame_cycles}, {"busy_cycles", json::object()}, {"last_cycle", json::object()}};
  for (const auto& b : r.blocks) j["busy_cycles"][b.name] = b.stats.busy_cycles, j["last_cycle"][b.name] = b.last_cycle;
  return j;
}

void check_accuracy(const core::Frame& frame, const core::Scene& scene, const json& spec) {
  const core::Frame ref = reference::to_frame(reference::render(scene));
  core::CompareOptions rgb;
  rgb.layers = {"RGB"};
  rgb.fail = spec.value("rgb_max", 0.0);
  const core::CompareResult accuracy = core::compare_frames(frame, ref, rgb);
  INFO("colour error against the golden model: " << accuracy.verdict() << " (gate: " << spec.dump() << ")");
  // Every gate the spec names (written so that NaN fails).
  if (spec.contains("rgb_min_psnr")) CHECK(accuracy.layers.at(0).psnr >= spec["rgb_min_psnr"].get<double>());
  if (spec.contains("rgb_max")) CHECK(accuracy.pass);
  CHECK((spec.contains("rgb_min_psnr") || spec.contains("rgb_max")));
  CHECK(frame.at("A") == ref.at("A"));  // identical coverage
}

// Regression of one frame against its accepted file; returns whether it was rewritten.
void check_regression(const core::Frame& frame, const core::Scene& scene, const json& thresholds,
                      const std::string& accepted, const std::string& scene_file) {
  bool pass = false;
  std::string verdict = "missing";
  if (std::filesystem::exists(accepted)) {
    const core::Frame golden = core::read_exr(accepted);
    core::CompareOptions colour, depth, normal;
    colour.layers = {"RGB", "A"}, colour.fail = thresholds["rgb"].get<double>();  // colour and coverage
    depth.layers = {"Z"}, depth.fail = thresholds["z"].get<double>();
    normal.layers = {"N"}, normal.fail = thresholds["n"].get<double>();
    const auto rc = core::compare_frames(frame, golden, colour), rz = core::compare_frames(frame, golden, depth),
               rn = core::compare_frames(frame, golden, normal);
    pass = rc.pass && rz.pass && rn.pass;
    verdict = rc.verdict() + " |" + rz.verdict() + " |" + rn.verdict();
  }
  if (!pass && regenerate()) {
    core::Frame out = frame;
    out.attributes["shadetlm:scene"] = scene_file;
    out.attributes["shadetlm:config"] = test::settings(scene).resolved().dump();
    core::write_exr(accepted, out);
    WARN("REGEN_GOLDEN: rewrote " << accepted << " (was: " << verdict << ")");
    return;
  }
  INFO("against " << accepted << ": " << verdict << " (REGEN_GOLDEN=1 rewrites it on purpose)");
  CHECK(pass);
}

void check_cycles(const modules::RenderResult& r, const json& spec, const std::string& accepted) {
  const json now = cycle_stats(r);
  bool pass = false;
  std::string then = "missing";
  if (std::filesystem::exists(accepted)) {
    std::ifstream in(accepted);
    const json stored = json::parse(in);
    then = stored.dump();
    const double tolerance = spec["tolerance"].get<double>();
    auto close = [&](double a, double b) { return std::abs(a - b) <= tolerance * std::max(1.0, std::abs(b)); };
    pass = close(double(now["frame_cycles"].get<uint64_t>()), double(stored["frame_cycles"].get<uint64_t>()));
    for (const char* figure : {"busy_cycles", "last_cycle"}) {
      pass = pass && stored.contains(figure) && stored[figure].size() == now[figure].size();
      for (const auto& [block, cycles] : now[figure].items())
        pass = pass && stored[figure].contains(block) &&
               close(double(cycles.get<int64_t>()), double(stored[figure][block].get<int64_t>()));
    }
  }
  if (!pass && regenerate()) {
    std::ofstream(accepted) << now.dump(2) << "\n";
    WARN("REGEN_GOLDEN: rewrote " << accepted << " (was: " << then << ")");
    return;
  }
  INFO("cycles now " << now.dump() << ", accepted " << then << " (tolerance " << spec["tolerance"] << ")");
  CHECK(pass);
}

void check_golden(const std::string& name) {
  test::route_systemc_reports_to_failures();
  const std::string dir = test::source_path("golden/" + name);
  std::ifstream in(dir + "/golden.json");
  REQUIRE(in);
  const json spec = json::parse(in);
  const std::string scene_file = "golden/" + name + "/scene.json";

  // The default configuration: SystemC, and the loop for equivalence.
  const core::Scene scene = core::load_scene(dir + "/scene.json");
  const modules::RenderResult pipeline = modules::render_systemc(scene);
  const modules::RenderResult loop = modules::render_loop(scene);
  REQUIRE(loop.frame.channels.size() == pipeline.frame.channels.size());
  for (const auto& c : pipeline.frame.channels) {
    INFO("channel " << c.name);
    CHECK(std::memcmp(c.values.data(), loop.frame.at(c.name).data(), c.values.size() * sizeof(float)) == 0);
  }
  check_accuracy(pipeline.frame, scene, spec["accuracy"]);
  check_regression(pipeline.frame, scene, spec["regression"], dir + "/frame.exr", scene_file);
  check_cycles(pipeline, spec["cycles"], dir + "/stats.json");

  // Further configurations, through the loop (SystemC elaborates once per process).
  if (spec.contains("configurations"))
    for (const auto& [config, c] : spec["configurations"].items()) {
      INFO("configuration " << config);
      const core::Scene variant = core::load_scene(dir + "/scene.json", c["set"].get<std::vector<std::string>>());
      const modules::RenderResult r = modules::render_loop(variant);
      check_accuracy(r.frame, variant, c["accuracy"]);
      check_regression(r.frame, variant, spec["regression"], dir + "/frame." + config + ".exr", scene_file);
    }
}

}  // namespace

TEST_CASE("golden sphere", "[golden][systemc]") { check_golden("sphere"); }
TEST_CASE("golden torus", "[golden][systemc]") { check_golden("torus"); }
TEST_CASE("golden knot", "[golden][systemc]") { check_golden("knot"); }
TEST_CASE("golden grazing-plane", "[golden][systemc]") { check_golden("grazing-plane"); }
TEST_CASE("golden point-light", "[golden][systemc]") { check_golden("point-light"); }
TEST_CASE("golden demo", "[golden][systemc]") { check_golden("demo"); }
TEST_CASE("golden bump-plane", "[golden][systemc]") { check_golden("bump-plane"); }
TEST_CASE("golden bump-sphere", "[golden][systemc]") { check_golden("bump-sphere"); }
TEST_CASE("golden bump-torus", "[golden][systemc]") { check_golden("bump-torus"); }
TEST_CASE("golden bump-knot", "[golden][systemc]") { check_golden("bump-knot"); }
TEST_CASE("golden bump-object", "[golden][systemc]") { check_golden("bump-object"); }
TEST_CASE("golden texture-object", "[golden][systemc]") { check_golden("texture-object"); }
TEST_CASE("golden texture-screen", "[golden][systemc]") { check_golden("texture-screen"); }
TEST_CASE("golden parallax-steps", "[golden][systemc]") { check_golden("parallax-steps"); }

TEST_CASE("every golden folder has its test case and its golden.json", "[golden]") {
  // A scene added to golden/ without a TEST_CASE above would never be checked by ctest.
  const std::set<std::string> covered = {"sphere",      "torus",       "knot",       "grazing-plane", "point-light",
                                         "demo",        "bump-plane",  "bump-sphere", "bump-torus",   "bump-knot",
                                         "bump-object", "texture-object", "texture-screen", "parallax-steps"};
  for (const auto& e : std::filesystem::directory_iterator(test::source_path("golden")))
    if (e.is_directory()) {
      INFO(e.path());
      CHECK(covered.count(e.path().filename().string()) == 1);
      CHECK(std::filesystem::exists(e.path() / "golden.json"));
    }
}

TEST_CASE("every golden configuration has its accepted frame and cycles", "[golden]") {
  // scripts/regress.sh compares each configuration's cycles with stats.<name>.json; one
  // missing fails the regression on every clean clone (the tests above run further
  // configurations through the loop, which has no cycles, so they would not notice).
  for (const auto& e : std::filesystem::directory_iterator(test::source_path("golden"))) {
    if (!e.is_directory()) continue;
    std::ifstream in(e.path() / "golden.json");
    const json spec = json::parse(in);
    CHECK(std::filesystem::exists(e.path() / "frame.exr"));
    CHECK(std::filesystem::exists(e.path() / "stats.json"));
    const json configs = spec.value("configurations", json::object());
    for (const auto& [config, c] : configs.items()) {
      INFO(e.path().filename().string() << " configuration " << config);
      CHECK(std::filesystem::exists(e.path() / ("frame." + config + ".exr")));
      CHECK(std::filesystem::exists(e.path() / ("stats." + config + ".json")));
    }
  }
}
