#pragma once
// Scanline traversal with an early depth test. Rows top to bottom, pixels left to
// right, exactly the pixels of the shared coverage convention (core/coverage.hpp). Each
// pixel's 1/w comes from its plane by one addition per step, re-seeded from the plane
// every kSpanMax pixels (so that rounding cannot build up along a long row). A pixel
// centre that snapping covers just outside the triangle, beyond the plane's vanishing
// line, gets 1/w ≤ 0 from the plane: it takes the triangle's smallest vertex 1/w
// instead, as the golden model takes the triangle's nearest point there.
// A pixel is visible when its 1/w is larger (nearer) than the depth buffer's, which it
// then replaces — so hidden fragments never reach the shading blocks. Runs of visible
// pixels go out as span packets of at most kSpanMax pixels, with w = 1/(1/w) for the
// blocks downstream (the one reciprocal per pixel of perspective-correct
// interpolation).
#include <vector>

#include "modules/common/packet.hpp"

namespace modules {

class RasterKernel {
 public:
  RasterKernel(int width, int height);

  // Calls emit(SpanPacket&) for each run of visible pixels of the triangle.
  template <class Emit>
  void run(const TriangleSetup& t, Emit&& emit);

  const Ops& ops() const { return ops_; }
  uint64_t pixels_walked() const { return walked_; }
  uint64_t row_walked_before() const { return row_before_; }  // walked before this row
  uint64_t pixels_hidden() const { return hidden_; }

  // Per pixel walked: the 1/w step (compares are free, as everywhere); per visible
  // pixel, the reciprocal; per seed (a row's first pixel, then every kSpanMax), the
  // plane evaluated.
  static constexpr Ops kOpsPerPixelWalked{/*add*/ 1};
  static constexpr Ops kOpsPerPixelVisible{0, 0, /*div*/ 1};
  static constexpr Ops kOpsPerSeed{/*add*/ 2, /*mul*/ 2};

 private:
  int width_, height_;
  std::vector<float> inv_depth_;
  SpanPacket packet_;
  Ops ops_;
  uint64_t walked_ = 0, hidden_ = 0, row_before_ = 0;
};

template <class Emit>
void RasterKernel::run(const TriangleSetup& t, Emit&& emit) {
  SpanPacket& p = packet_;
  p.tri = &t;
  for (int y = t.coverage.y0; y <= t.coverage.y1; ++y) {
    const auto [x_begin, x_end] = t.coverage.row_span(y);
    if (x_begin >= x_end) continue;
    const uint64_t n = uint64_t(x_end - x_begin);
    row_before_ = walked_;
    walked_ += n;
    ops_ += kOpsPerPixelWalked * n + kOpsPerSeed * ((n + kSpanMax - 1) / kSpanMax);
    float inv_w = 0;
    float* depth = &inv_depth_[size_t(y) * width_];
    p.y = y;
    p.row_start = x_begin;
    p.count = 0;
    for (int x = x_begin; x < x_end; ++x, inv_w += t.inv_w.ax) {
      static_assert((kSpanMax & (kSpanMax - 1)) == 0, "re-seeding uses a mask");
      if (((x - x_begin) & (kSpanMax - 1)) == 0) inv_w = t.inv_w.at(x - t.x_ref, y - t.y_ref);
      const float inv_w_pixel = inv_w > 0 ? inv_w : t.inv_w_min;
      if (inv_w_pixel > depth[x]) {
        depth[x] = inv_w_pixel;
        if (p.count == 0) p.x0 = x;
        p.inv_w[p.count] = inv_w_pixel;
        p.w[p.count] = 1.0f / inv_w_pixel;
        if (++p.count == kSpanMax) {
          ops_ += kOpsPerPixelVisible * uint64_t(p.count);
          emit(p);
          p.count = 0;
        }
      } else {
        ++hidden_;
        if (p.count > 0) {  // a hidden pixel ends the run
          ops_ += kOpsPerPixelVisible * uint64_t(p.count);
          emit(p);
          p.count = 0;
        }
      }
    }
    if (p.count > 0) {
      ops_ += kOpsPerPixelVisible * uint64_t(p.count);
      emit(p);
    }
  }
}

}  // namespace modules
