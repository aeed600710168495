// Testbench of normal_interp (normal-increments paper, claim 1): the normals the
// walker builds by adding ΔN_H, ΔN_V, ΔN_D (and ΔN_A) equal the directly interpolated
// ones — the triangle's plane evaluated at each pixel — within the rounding bound of
// float addition, on random triangles (split ones included) partly hidden by
// occluders, so that the walker also steps through hidden pixels and empty rows.
//
// The bound: every step is one float addition, which rounds by at most u·|result|
// (u = 2⁻²⁴); the diagonal increments ΔN_D = ΔN_H + ΔN_V and ΔN_A are themselves
// rounded sums, off by at most u·|Δ|. A pixel reached after k steps is therefore off
// by at most k·u·(M + D), M the largest |component| of the walk, D the largest |Δ|.
// k is at most the steps the walker took for the whole triangle.
#include <random>

#include "shadetlm/modules/normal_interp/normal_interp_kernel.hpp"
#include "shadetlm/modules/raster/raster_kernel.hpp"
#include "shadetlm/modules/setup/setup_kernel.hpp"
#include "systemc_harness.hpp"

using namespace shadetlm;  // core::, modules::, reference::

namespace {
constexpr int W = 256, H = 256;

// A triangle's setup built from screen positions and per-vertex values of N: the
// walker's input, as the setup block would produce it.
bool make_setup(const glm::dvec2 s[3], const glm::dvec3 n[3], float inv_w, uint32_t id, modules::TriangleSetup& t) {
  if (!core::snap_triangle(s[0], s[1], s[2], W, H, t.coverage)) return false;
  bool found = false;
  for (int y = t.coverage.y0; y <= t.coverage.y1 && !found; ++y) {
    auto [b, e] = t.coverage.row_span(y);
    if (b < e) t.x_ref = b, t.y_ref = y, found = true;
  }
  if (!found) return false;
  const int* src = t.coverage.source.data();
  modules::PlaneSolver<float> ps;
  ps.dx1 = float(s[src[1]].x - s[src[0]].x), ps.dy1 = float(s[src[1]].y - s[src[0]].y);
  ps.dx2 = float(s[src[2]].x - s[src[0]].x), ps.dy2 = float(s[src[2]].y - s[src[0]].y);
  ps.inv_det = 1.0f / (ps.dx1 * ps.dy2 - ps.dx2 * ps.dy1);
  ps.ox = float(t.x_ref + 0.5 - s[src[0]].x), ps.oy = float(t.y_ref + 0.5 - s[src[0]].y);
  for (int c = 0; c < 3; ++c) {
    ps.solve(float(n[src[0]][c]), float(n[src[1]][c]), float(n[src[2]][c]), t.n[c].a0, t.n[c].ax, t.n[c].ay);
    t.dn_d[c] = t.n[c].ax + t.n[c].ay;
    t.dn_a[c] = t.n[c].ay - t.n[c].ax;
  }
  t.inv_w = {inv_w, 0, 0};
  t.id = id;
  return true;
}
}  // namespace

TEST_CASE("normal_interp: constant increments equal direct interpolation within the rounding bound",
          "[normal_interp][systemc]") {
  modules::NormalInterpKernel kernel;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> pos(-20, W + 20), comp(-1, 1);
  std::vector<modules::TriangleSetup> setups(400);
  uint64_t pixels = 0, hidden_steps = 0, triangles = 0;
  double worst_ratio = 0;  // error / bound, over all pixels
  uint64_t steps_at_start = 0;
  const modules::TriangleSetup* current = nullptr;
  const double u = std::ldexp(1.0, -24);

  auto produce = [&](std::function<void(modules::SpanPacket&)> send) {
    uint32_t id = 0;
    for (auto& t : setups) {
      glm::dvec2 s[3];
      glm::dvec3 n[3];
      for (int k = 0; k < 3; ++k) s[k] = {pos(rng), pos(rng)}, n[k] = {comp(rng), comp(rng), comp(rng)};
      if (id % 4 == 0) s[1].y = s[0].y;  // flat top or bottom: one half of a split
      if (!make_setup(s, n, 1.0f, id, t)) continue;
      // A fresh depth buffer with an occluder in front (1/w = 2): the walk must cross
      // the hidden pixels it leaves.
      modules::RasterKernel raster(W, H);
      modules::TriangleSetup occluder;
      glm::dvec2 o[3] = {{pos(rng), pos(rng)}, {pos(rng), pos(rng)}, {pos(rng), pos(rng)}};
      if (make_setup(o, n, 2.0f, ~0u - 1, occluder)) raster.run(occluder, [](modules::SpanPacket&) {});
      current = &t;
      steps_at_start = kernel.steps();
      raster.run(t, send);
      hidden_steps += raster.pixels_hidden();
      ++triangles;
      ++id;
    }
  };
  // The walk's largest component and increment, for the bound, and the path length
  // (all the walker's steps for this triangle so far).
  auto check = [&](const modules::SpanPacket& p) {
    const modules::TriangleSetup& t = *current;
    const double k = double(kernel.steps() - steps_at_start);
    double M = 0, D = 0;
    for (int c = 0; c < 3; ++c) {
      D = std::max({D, std::abs(double(t.n[c].ax)), std::abs(double(t.n[c].ay)), std::abs(double(t.dn_d[c])),
                    std::abs(double(t.dn_a[c]))});
      // |plane| is largest at a corner of the triangle's pixel box.
      for (int cy : {t.coverage.y0, t.coverage.y1})
        for (int cx : {t.coverage.x0, t.coverage.x1})
          M = std::max(M, std::abs(double(t.n[c].a0) + double(t.n[c].ax) * (cx - t.x_ref) +
                                   double(t.n[c].ay) * (cy - t.y_ref)));
    }
    const double bound = k * u * (M + D) + 1e-30;
    for (int i = 0; i < p.count; ++i) {
      const int dx = p.x0 + i - t.x_ref, dy = p.y - t.y_ref;
      for (int c = 0; c < 3; ++c) {
        const double direct = double(t.n[c].a0) + double(t.n[c].ax) * dx + double(t.n[c].ay) * dy;
        const double err = std::abs(double(p.n[c][i]) - direct);
        REQUIRE(err <= bound);
        worst_ratio = std::max(worst_ratio, err / bound);
      }
    }
    pixels += uint64_t(p.count);
  };
  test::run_stage(kernel, produce, check);

  INFO("worst error / bound = " << worst_ratio);
  CHECK(triangles > 300);
  CHECK(pixels > 100000);
  CHECK(hidden_steps > 10000);   // the occluders really made the walker skip
  CHECK(worst_ratio > 0);        // rounding happened: the check is not vacuous
}

TEST_CASE("normal_interp: one step per pixel and row, three additions per step", "[normal_interp]") {
  // A triangle with a vertical left edge through pixel column 10 (x = 10.2): every row
  // starts at x = 10, so the walker takes one ΔN_V step per row after the first and one
  // ΔN_H step per pixel — counted here from the coverage alone, not from the kernel.
  const glm::dvec2 s[3] = {{10.2, 10.2}, {10.2, 40.2}, {50.2, 10.2}};
  const glm::dvec3 n[3] = {{0, 0, 1}, {0.5, 0, 1}, {0, 0.5, 1}};
  modules::TriangleSetup t;
  REQUIRE(make_setup(s, n, 1.0f, 0, t));
  modules::RasterKernel raster(W, H);
  modules::NormalInterpKernel kernel;
  uint64_t pixels = 0, rows = 0;
  raster.run(t, [&](modules::SpanPacket& p) {
    CHECK(p.row_start == 10);
    kernel.process(p);
    pixels += uint64_t(p.count);
  });
  for (int y = t.coverage.y0; y <= t.coverage.y1; ++y) {
    auto [b, e] = t.coverage.row_span(y);
    rows += b < e;
  }
  REQUIRE(rows == 30);
  CHECK(kernel.steps() == (rows - 1) + pixels);
  CHECK(kernel.ops() == modules::Ops{3 * ((rows - 1) + pixels)});
}
