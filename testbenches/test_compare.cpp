// Frame comparison: metrics, the pass/fail rule, structural mismatches.
#include <cmath>

#include "shadetlm/core/compare.hpp"
#include "test_util.hpp"

using namespace shadetlm;  // core::, modules::, reference::

namespace {
core::Frame frame(int w, int h, float value) {
  core::Frame f(w, h);
  for (const char* n : {"R", "G", "B", "A", "Z", "N.X", "N.Y", "N.Z"}) f.add(n, value);
  return f;
}
const core::LayerMetrics& layer(const core::CompareResult& r, const std::string& name) {
  for (const auto& m : r.layers)
    if (m.layer == name) return m;
  FAIL("no layer " << name);
  throw;
}
}  // namespace

TEST_CASE("identical frames pass with zero error and infinite PSNR", "[compare]") {
  const core::Frame a = frame(8, 4, 0.5f);
  const auto r = core::compare_frames(a, a, {});
  CHECK(r.pass);
  REQUIRE(r.layers.size() == 3);
  for (const auto& m : r.layers) {
    CHECK(m.max_abs == 0);
    CHECK(std::isinf(m.psnr));
  }
}

TEST_CASE("one changed pixel is found, measured and located", "[compare]") {
  const core::Frame b = frame(8, 4, 0.5f);
  core::Frame a = b;
  a.at("G")[2 * 8 + 5] += 0.25f;  // pixel (5, 2)
  const auto r = core::compare_frames(a, b, {});
  CHECK(!r.pass);
  const auto& rgb = layer(r, "RGB");
  CHECK(rgb.max_abs == Approx(0.25));
  CHECK(rgb.max_x == 5);
  CHECK(rgb.max_y == 2);
  CHECK(rgb.over == 1);
  // RMSE over the 32 pixels × 4 channels of the layer.
  CHECK(rgb.rmse == Approx(std::sqrt(0.0625 / 128)));
  CHECK(rgb.psnr == Approx(10 * std::log10(128 / 0.0625)));
  CHECK(layer(r, "Z").pass);
  CHECK(layer(r, "N").pass);
}

TEST_CASE("fail, failpercent and hardfail follow idiff's rule", "[compare]") {
  const core::Frame b = frame(10, 10, 0.0f);
  core::Frame a = b;
  for (int i = 0; i < 5; ++i) a.at("R")[i] = 0.01f;  // 5 % of the pixels off by 0.01
  core::CompareOptions o;
  o.layers = {"RGB"};
  o.fail = 0.02;
  CHECK(core::compare_frames(a, b, o).pass);   // under the per-pixel threshold
  o.fail = 0.005;
  CHECK(!core::compare_frames(a, b, o).pass);  // 5 % over, 0 % allowed
  o.fail_percent = 5;
  CHECK(core::compare_frames(a, b, o).pass);   // 5 % over, 5 % allowed
  o.hard_fail = 0.009;
  CHECK(!core::compare_frames(a, b, o).pass);  // but one pixel is over the hard limit
}

TEST_CASE("infinite depth matches infinite depth, and nothing else", "[compare]") {
  core::Frame b = frame(2, 1, 1.0f);
  b.at("Z")[0] = std::numeric_limits<float>::infinity();
  core::Frame a = b;
  core::CompareOptions o;
  o.layers = {"Z"};
  CHECK(core::compare_frames(a, b, o).pass);
  a.at("Z")[0] = 3.0f;
  const auto r = core::compare_frames(a, b, o);
  CHECK(!r.pass);
  CHECK(std::isinf(layer(r, "Z").max_abs));
}

TEST_CASE("resolution and channel mismatches fail before any metric", "[compare]") {
  CHECK(!core::compare_frames(frame(4, 4, 0), frame(4, 5, 0), {}).pass);
  CHECK_THAT(core::compare_frames(frame(4, 4, 0), frame(4, 5, 0), {}).problem, Catch::Contains("resolution"));
  core::Frame a = frame(4, 4, 0), b;
  b.width = 4;
  b.height = 4;
  for (const char* n : {"R", "G", "B", "A", "Z"}) b.add(n, 0);
  const auto r = core::compare_frames(a, b, {});
  CHECK(!r.pass);
  CHECK_THAT(r.problem, Catch::Contains("N.X"));
  core::CompareOptions only_rgb;
  only_rgb.layers = {"RGB"};
  CHECK(core::compare_frames(a, b, only_rgb).pass);  // N is not asked for
}

TEST_CASE("frames with no layer in common fail", "[compare]") {
  core::Frame a(2, 2), b(2, 2);
  a.add("Y", 0.0f);
  b.add("Y", 1.0f);
  const auto r = core::compare_frames(a, b, {});
  CHECK(!r.pass);
  CHECK_THAT(r.problem, Catch::Contains("no layer"));
}

TEST_CASE("the difference frame holds |A - B| per channel", "[compare]") {
  const core::Frame b = frame(3, 1, 1.0f);
  core::Frame a = b;
  a.at("B")[1] = 0.25f;
  const auto r = core::compare_frames(a, b, {});
  const core::Frame d = core::difference_frame(a, b, r);
  CHECK(d.at("B") == std::vector<float>{0, 0.75f, 0});
  CHECK(d.at("R") == std::vector<float>{0, 0, 0});
}
