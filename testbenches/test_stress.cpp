// The numerical-stability stress scenes (scenes/stress/, written by
// scripts/make-stress-scenes.py): long spans, tall triangles, slivers and degenerate
// triangles, nearly opposite and near-zero normals, coordinates at ±1e6, the near plane,
// grazing views, full-depth height steps. No NaN or infinity may reach a frame — the
// pipeline's or the golden model's — and coverage must be the golden model's.
#include <cmath>
#include <filesystem>

#include "modules/pipeline/pipeline.hpp"
#include "reference/reference.hpp"
#include "test_util.hpp"

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
    CHECK(r.stats_json()["nonfinite_written"].get<uint64_t>() == 0);
    CHECK(nonfinite(ref) == 0);
    CHECK(r.frame.at("A") == ref.at("A"));
  }
  CHECK(scenes >= 16);
}
