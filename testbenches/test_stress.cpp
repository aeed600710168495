// The numerical-stability stress scenes (scenes/stress/, written by
// scripts/make-stress-scenes.py): long spans, tall triangles, slivers and degenerate
// triangles, nearly opposite and near-zero normals, coordinates at ±1e6, the near plane,
// grazing views, full-depth height steps. No NaN or infinity may reach a frame — the
// pipeline's or the golden model's — and coverage must be the golden model's.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "shadetlm/core/compare.hpp"
#include "shadetlm/modules/pipeline/pipeline.hpp"
#include "shadetlm/reference/reference.hpp"
#include "test_util.hpp"

using namespace shadetlm;  // core::, modules::, reference::

namespace {

// Non-finite values in the covered pixels of a frame (depth is +inf where nothing is).
size_t nonfinite(const core::Frame& f) {
  size_t bad = 0;
  const auto& a = f.find("A")->values;
  for (const auto& c : f.channels)
    for (size_t i = 0; i < c.values.size(); ++i)
      if (a[i] > 0 && !std::isfinite(c.values[i])) ++bad;
  return bad;
}

}  // namespace

TEST_CASE("stress scenes: no NaN or infinity reaches a frame, and coverage is the golden model's", "[stress]") {
  int scenes = 0;
  for (const auto& entry : std::filesystem::directory_iterator(test::source_path("scenes/stress"))) {
    if (entry.path().extension() != ".json") continue;
    INFO(entry.path().filename());
    ++scenes;
    const core::Scene scene = core::load_scene(entry.path().string());
    const modules::RenderResult r = modules::render_loop(scene);
    const core::Frame ref = reference::to_frame(reference::render(scene));
    CHECK(nonfinite(r.frame) == 0);
    CHECK(r.stats_json()["nonfinite_replaced"].get<uint64_t>() == 0);
    CHECK(nonfinite(ref) == 0);
    CHECK(r.frame.at("A") == ref.at("A"));
    // In float32 no block that tests its outputs puts out a NaN or an infinity. (The
    // walker, lighting and texel_project do not test in float32: null. Events are
    // counted in reduced formats only.)
    const auto stats = r.stats_json();
    for (const auto& [block, b] : stats["blocks"].items())
      if (b.contains("numbers")) {
        INFO(block);
        const bool untested = block == "normal_interp" || block == "lighting" || block == "texel_project";
        CHECK(b["numbers"]["nonfinite"] == (untested ? nlohmann::json() : nlohmann::json(0)));
      }
  }
  CHECK(scenes >= 19);
}

TEST_CASE("stress scenes in float16 and in narrow fixed point: whatever the blocks meet, no NaN or infinity reaches the frame",
          "[stress]") {
  for (const auto& entry : std::filesystem::directory_iterator(test::source_path("scenes/stress"))) {
    if (entry.path().extension() != ".json") continue;
    for (const std::string format : {"float16", "fixed:2.8"}) {
      INFO(entry.path().filename() << " in " << format);
      const core::Scene scene = core::load_scene(entry.path().string(), {"pipeline.number_format=" + format});
      const modules::RenderResult r = modules::render_loop(scene);
      CHECK(nonfinite(r.frame) == 0);
      // What reached the framebuffer was put out by some block, which counted it.
      const auto stats = r.stats_json();
      CHECK(stats["numbers"]["nonfinite"].get<uint64_t>() >= (stats["nonfinite_replaced"].get<uint64_t>() > 0 ? 1u : 0u));
      if (format == "fixed:2.8") CHECK(stats["numbers"]["nonfinite"] == 0);  // fixed point saturates, never NaN
    }
  }
}

TEST_CASE("re-seeding the normal walker bounds its error on long spans and tall triangles", "[stress]") {
  auto normal_error = [](const std::string& scene, const std::string& reseed) {
    const core::Scene s = core::load_scene(test::source_path("scenes/stress/" + scene),
                                           {"pipeline.normal_interp.reseed=" + reseed});
    core::CompareOptions o;
    o.layers = {"N"};
    return core::compare_frames(modules::render_loop(s).frame, reference::to_frame(reference::render(s)), o)
        .layers.at(0)
        .max_abs;
  };
  // Along a 16384-pixel span the error grows with the steps; tiles of 32 bound it.
  const double span_none = normal_error("long-spans.json", "none"), span_tile = normal_error("long-spans.json", "tile32");
  INFO("long spans: none " << span_none << ", tile32 " << span_tile);
  CHECK(span_tile < span_none / 10);
  // Down 16384 rows the edge walk accumulates; re-seeding each row start bounds it.
  const double tall_none = normal_error("tall-triangle.json", "none"), tall_line = normal_error("tall-triangle.json", "line");
  INFO("tall triangle: none " << tall_none << ", line " << tall_line);
  CHECK(tall_line < tall_none / 10);
}

TEST_CASE("a radicand carried along the line that would reach zero is dropped for a seed: no non-finite normal",
          "[stress]") {
  // Between nearly opposite normals |N|² passes near zero, and the float32 rounding that
  // seed=line carries along a line took R below it (6 non-finite normals before the guard).
  const core::Scene s = core::load_scene(test::source_path("scenes/stress/opposite-normals.json"),
                                         {"pipeline.normalize.mode=forward-difference", "pipeline.normalize.seed=line"});
  const modules::RenderResult r = modules::render_loop(s);
  const auto normalize = std::find_if(r.blocks.begin(), r.blocks.end(), [](const auto& b) { return b.name == "normalize"; });
  REQUIRE(normalize != r.blocks.end());
  REQUIRE(normalize->numbers);
  CHECK(normalize->numbers->nonfinite == 0);
  const uint64_t reseeds = normalize->details.at("reseeds").get<uint64_t>();
  INFO("re-seeds " << reseeds << " of " << normalize->details.at("seeds").get<uint64_t>() << " seeds");
  CHECK(reseeds > 0);
  CHECK(reseeds <= normalize->details.at("seeds").get<uint64_t>());
  CHECK(r.nonfinite_replaced == 0);
}
