// Frame comparison: metrics, the pass/fail rule, structural mismatches.
#include <cmath>
#include <limits>
#include <string>

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
  REQUIRE(r.layers.size() == 4);  // RGB, A, Z, N
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
  // RMSE over the 32 pixels (all covered: A = 0.5) × 3 channels of the layer.
  CHECK(rgb.pixels == 32);
  CHECK(rgb.rmse == Approx(std::sqrt(0.0625 / 96)));
  CHECK(rgb.psnr == Approx(10 * std::log10(96 / 0.0625)));
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

// The figures over the covered pixels, computed here without compare.cpp's code: two
// frames with their own coverage (some pixels covered in one only), random colours.
TEST_CASE("the figures are over the pixels covered in either frame, R, G, B only", "[compare]") {
  const int w = 23, h = 17;
  core::Frame a(w, h), b(w, h);
  uint32_t state = 12345;
  auto next = [&]() { return (state = state * 1664525u + 1013904223u) >> 8; };
  for (core::Frame* f : {&a, &b})
    for (const char* n : {"R", "G", "B", "A"}) {
      auto& v = f->add(n);
      for (auto& x : v) x = std::string(n) == "A" ? float(next() % 3 != 0) : float(next() % 1000) / 1000.0f;
    }
  // Reference: a plain loop over the pixels covered in either frame.
  double sum = 0, largest = 0, frame_sum = 0;
  size_t covered = 0, differ = 0;
  for (size_t i = 0; i < a.pixel_count(); ++i) {
    double sq = 0, e = 0;
    for (const char* n : {"R", "G", "B"}) {
      const double d = double(a.at(n)[i]) - double(b.at(n)[i]);
      sq += d * d;
      e = std::max(e, std::abs(d));
    }
    frame_sum += sq;
    const bool ca = a.at("A")[i] != 0, cb = b.at("A")[i] != 0;
    differ += ca != cb;
    if (!ca && !cb) continue;
    ++covered, sum += sq, largest = std::max(largest, e);
  }
  const auto r = core::compare_frames(a, b, {});
  const auto& rgb = layer(r, "RGB");
  CHECK(r.coverage.source == "A");
  CHECK(r.coverage.either == covered);
  CHECK(r.coverage.differ == differ);
  CHECK(rgb.channels == std::vector<std::string>{"R", "G", "B"});
  CHECK(rgb.pixels == covered);
  CHECK(rgb.max_abs == Approx(largest));
  CHECK(rgb.rmse == Approx(std::sqrt(sum / (3.0 * double(covered)))));
  CHECK(rgb.psnr == Approx(10 * std::log10(3.0 * double(covered) / sum)));
  CHECK(rgb.frame_rmse == Approx(std::sqrt(frame_sum / (3.0 * w * h))));
  CHECK(covered < a.pixel_count());  // the mask took pixels out
  CHECK(rgb.rmse != Approx(rgb.frame_rmse));
}

TEST_CASE("without A a finite depth is coverage; without either every pixel counts", "[compare]") {
  core::Frame a(4, 1), b(4, 1);
  const float inf = std::numeric_limits<float>::infinity();
  for (core::Frame* f : {&a, &b}) {
    for (const char* n : {"R", "G", "B"}) f->add(n, 0.0f);
    f->add("Z", inf);
  }
  a.at("Z")[1] = 2;  // pixel 1 covered in A only
  a.at("R")[1] = 0.5f;
  a.at("R")[3] = 0.5f;  // a background difference: outside the figures, inside the verdict
  auto r = core::compare_frames(a, b, {});
  CHECK(r.coverage.source == "Z");
  CHECK(layer(r, "RGB").pixels == 1);
  CHECK(layer(r, "RGB").rmse == Approx(std::sqrt(0.25 / 3)));
  CHECK(layer(r, "RGB").over == 2);
  CHECK(!r.pass);
  core::CompareOptions rgb;
  rgb.layers = {"RGB"};
  a.channels.pop_back(), b.channels.pop_back();  // no Z: every pixel counts
  r = core::compare_frames(a, b, rgb);
  CHECK(r.coverage.source == "none");
  CHECK(layer(r, "RGB").pixels == 4);
  CHECK(layer(r, "RGB").rmse == Approx(std::sqrt(0.5 / 12)));
}

TEST_CASE("a frame without A compares with one that has it on the layers both have; empty coverage has no figure", "[compare]") {
  core::Frame a(3, 1), b(3, 1);
  for (core::Frame* f : {&a, &b})
    for (const char* n : {"R", "G", "B"}) f->add(n, 0.5f);
  a.add("A", 1.0f);  // a pipeline frame against an RGB-only reference
  CHECK(core::compare_frames(a, b, {}).pass);
  core::CompareOptions alpha;
  alpha.layers = {"A"};
  CHECK(!core::compare_frames(a, b, alpha).pass);  // asked for: required in both
  // Nothing covered in either frame: the figures are NaN, so no PSNR gate passes on them.
  a.at("A").assign(3, 0.0f);
  b.add("A", 0.0f);
  const auto r = core::compare_frames(a, b, {});
  CHECK(r.pass);  // the verdict: no pixel differs
  CHECK(layer(r, "RGB").pixels == 0);
  CHECK(std::isnan(layer(r, "RGB").psnr));
  CHECK(!(layer(r, "RGB").psnr >= 0));
}
