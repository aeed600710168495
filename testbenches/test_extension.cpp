// The extension point (docs/development.md, "Adding a block"): a block declared here,
// outside modules/, added to the standard pipeline by one call, elaborated by both
// engines, with its own setting, statistics and timing.
#include "shadetlm/tlm/block.hpp"
#include "shadetlm/modules/pipeline/pipeline.hpp"
#include "test_util.hpp"

using namespace shadetlm;  // core::, modules::, reference::

namespace {

// A testbench-only block: scales every pixel's colour by pipeline.tint.gain and counts
// the pixels it tinted.
class TintKernel {
 public:
  static constexpr unsigned optional = modules::Optional::details;  // (tlm/kernel_parts.hpp)
  explicit TintKernel(double gain) : gain_(float(gain)) {}
  void process(modules::SpanPacket& p) {
    for (int c = 0; c < 3; ++c)
      for (int i = 0; i < p.count; ++i) p.rgb[c][i] *= gain_;
    ops_.mul += 3 * uint64_t(p.count);
    tinted_ += uint64_t(p.count);
  }
  bool bypass(const modules::SpanPacket&) const { return false; }
  modules::Work work(const modules::SpanPacket&) const { return {nullptr, 1}; }  // a pixel a cycle
  const modules::Ops& ops() const { return ops_; }
  void set_capture(bool) {}
  static std::vector<std::string> trace_names() { return {"r"}; }
  void trace(const modules::SpanPacket& p, int i, double* out) const { out[0] = p.rgb[0][i]; }
  nlohmann::json details() const { return {{"tinted", tinted_}}; }

 private:
  float gain_;
  modules::Ops ops_;
  uint64_t tinted_ = 0;
};

struct TintSettings {
  static constexpr const char* block = "tint";
  double gain = 1.0;
  template <class F>
  void fields(F& f) {
    f(gain, "gain", {0, 10}, "colour gain");
  }
};

modules::BlockDecl tint_block() {
  modules::BlockDecl d = modules::declare<TintSettings>();
  d.basics.timing = {3, 1};
  d.make = [](const modules::BlockContext& ctx) -> std::unique_ptr<modules::Block> {
    return std::make_unique<modules::SpanBlock<TintKernel>>(float(ctx.read<TintSettings>().gain));
  };
  return d;
}

modules::PipelineDecl with_tint() {
  modules::PipelineDecl d = modules::standard_pipeline();
  d.insert_after("lighting", tint_block());
  return d;
}

const std::vector<std::string> kTintSettings = {"pipeline.tint.gain=0.5", "pipeline.tint.ii=2"};

core::Scene sphere(const std::vector<std::string>& more = {}) {
  std::vector<std::string> sets = {"camera.resolution=[64,48]"};
  sets.insert(sets.end(), more.begin(), more.end());
  return core::load_scene(test::source_path("golden/sphere/scene.json"), sets);
}

// The tinted frame is the plain one at half the colour (×0.5 is exact in float), alpha
// and depth unchanged; the block's statistics say what it did.
void check_tinted(const modules::RenderResult& tinted, const modules::RenderResult& plain) {
  for (const char* c : {"R", "G", "B"})
    for (size_t i = 0; i < plain.frame.at(c).size(); ++i) REQUIRE(tinted.frame.at(c)[i] == 0.5f * plain.frame.at(c)[i]);
  CHECK(tinted.frame.at("A") == plain.frame.at("A"));
  CHECK(tinted.frame.at("Z") == plain.frame.at("Z"));
  const auto stats = tinted.stats_json();
  const auto& names = stats["elaborated"];
  REQUIRE(std::find(names.begin(), names.end(), "tint") != names.end());
  CHECK(*(std::find(names.begin(), names.end(), "tint") + 1) == "framebuffer");
  const auto& tint = stats["blocks"]["tint"];
  CHECK(tint["details"]["tinted"] == plain.pixels_shaded);
  CHECK(tint["ops"]["mul"] == 3 * plain.pixels_shaded);
  CHECK(tint["ii"] == 2);  // its timing setting, given in the scene
  CHECK(tint["latency"] == 3);  // its declared default
}

}  // namespace

TEST_CASE("a block from outside modules/ runs in the loop engine with its setting and statistics", "[extension]") {
  const core::Scene scene = sphere(kTintSettings);
  const core::Scene plain_scene = sphere();
  const modules::RenderResult plain = modules::render_loop(plain_scene);
  REQUIRE(plain.pixels_shaded > 1000);
  check_tinted(modules::render_loop(scene, with_tint()), plain);
}

TEST_CASE("a block from outside modules/ runs in the SystemC engine, its cycles from its timing", "[extension]") {
  const core::Scene scene = sphere(kTintSettings);
  const core::Scene plain_scene = sphere();
  const modules::RenderResult plain = modules::render_loop(plain_scene);
  const modules::RenderResult tinted = modules::render_systemc(scene, with_tint());
  check_tinted(tinted, plain);
  // II 2 a pixel: its busy cycles are twice the pixels it tinted.
  CHECK(tinted.stats_json()["blocks"]["tint"]["busy_cycles"] == 2 * plain.pixels_shaded);
}

TEST_CASE("a block's settings are checked against its declaration", "[extension][bad]") {
  // Unknown to the standard pipeline, which has no tint block.
  try {
    test::settings(sphere({"pipeline.tint.gain=0.5"}));
    FAIL("the standard pipeline took a tint setting");
  } catch (const core::InputError& e) {
    CHECK(e.field() == "pipeline.tint.gain");
  }
  // Out of the range the block declared.
  const core::Scene scene = sphere({"pipeline.tint.gain=-1"});
  try {
    modules::Pipeline p(scene, with_tint());
    FAIL("a negative gain was accepted");
  } catch (const core::InputError& e) {
    CHECK(e.field() == "pipeline.tint.gain");
  }
  // A second block of the same name, or after a block that is not there, is refused.
  modules::PipelineDecl d = with_tint();
  CHECK_THROWS_AS(d.insert_after("lighting", tint_block()), std::invalid_argument);
  modules::BlockDecl other = tint_block();
  other.name = "other";
  CHECK_THROWS_AS(d.insert_after("shadow_map", other), std::invalid_argument);
}
