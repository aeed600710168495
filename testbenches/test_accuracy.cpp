// Accuracy where the golden scenes (at most 128 pixels wide) cannot look: rows of
// 1920 pixels, where any rounding that builds up along a row (the raster's 1/w, the
// interpolators) would show. A wall receding across the whole frame, lit by a point
// light (L and V interpolated per pixel), untextured: every pixel's colour within 2⁻¹²
// of the golden model, identical coverage. (Textured, the same wall shows the texture
// unit's float addressing at texel coordinates up to 2048: reported in
// docs/pipeline.md, not gated.)
#include <cstring>

#include "shadetlm/core/compare.hpp"
#include "shadetlm/modules/pipeline/pipeline.hpp"
#include "shadetlm/reference/reference.hpp"
#include "systemc_harness.hpp"
#include "test_util.hpp"

using namespace shadetlm;  // core::, modules::, reference::

TEST_CASE("long rows: a wall receding across 1920 pixels stays within 2^-12", "[accuracy][systemc]") {
  test::route_systemc_reports_to_failures();
  const core::Scene scene = core::load_scene(test::source_path("scenes/wide-wall.json"), {"objects.0.material=plain"});
  const modules::RenderResult r = modules::render_systemc(scene);
  REQUIRE(r.pixels_shaded > 100000);
  const core::Frame ref = reference::to_frame(reference::render(scene));
  core::CompareOptions o;
  o.layers = {"RGB"};
  o.fail = std::ldexp(1.0, -12);
  const core::CompareResult c = core::compare_frames(r.frame, ref, o);
  INFO(c.verdict());
  CHECK(c.pass);
  CHECK(r.frame.at("A") == ref.at("A"));
}

TEST_CASE("the same scene renders to the same bits, run after run", "[determinism]") {
  // Two runs in one process (kernel loop; the golden tests show the SystemC run equal
  // to it, and the golden frames tie runs of different processes and machines).
  const core::Scene scene = core::load_scene(test::source_path("golden/demo/scene.json"));
  const modules::RenderResult a = modules::render_loop(scene), b = modules::render_loop(scene);
  REQUIRE(a.frame.channels.size() == b.frame.channels.size());
  for (const auto& c : a.frame.channels) {
    INFO(c.name);
    CHECK(std::memcmp(c.values.data(), b.frame.at(c.name).data(), c.values.size() * sizeof(float)) == 0);
  }
  CHECK(a.total_ops() == b.total_ops());
}
