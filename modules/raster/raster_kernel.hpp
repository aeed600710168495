#pragma once
// Scanline traversal with an early depth test. Rows top to bottom, pixels left to
// right, exactly the pixels of the shared coverage convention (core/coverage.hpp). Each
// pixel's 1/w comes from its plane by one addition per step; a pixel is visible when
// its 1/w is larger (nearer) than the depth buffer's, which it then replaces — so
// hidden fragments never reach the shading blocks. Runs of visible pixels go out as
// span packets of at most kSpanMax pixels, with w = 1/(1/w) for the blocks downstream
// (the one reciprocal per pixel of perspective-correct interpolation).
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
  uint64_t pixels_hidden() const { return hidden_; }
  const std::vector<float>& depth_buffer() const { return inv_depth_; }  // 1/w, 0 = empty

  // Per pixel walked: the 1/w step and the depth compare (a subtraction);
  // per visible pixel, the reciprocal.
  static constexpr Ops kOpsPerPixelWalked{/*add*/ 2};
  static constexpr Ops kOpsPerPixelVisible{0, 0, /*div*/ 1};
  // Per row: the 1/w seed at the row's first pixel.
  static constexpr Ops kOpsPerRow{/*add*/ 2, /*mul*/ 2};

 private:
  int width_, height_;
  std::vector<float> inv_depth_;
  SpanPacket packet_;
  Ops ops_;
  uint64_t walked_ = 0, hidden_ = 0;
};

template <class Emit>
void RasterKernel::run(const TriangleSetup& t, Emit&& emit) {
  SpanPacket& p = packet_;
  p.tri = &t;
  for (int y = t.coverage.y0; y <= t.coverage.y1; ++y) {
    const auto [x_begin, x_end] = t.coverage.row_span(y);
    if (x_begin >= x_end) continue;
    ops_ += kOpsPerRow;
    const uint64_t n = uint64_t(x_end - x_begin);
    walked_ += n;  // counted as the row starts, so that a packet knows how far the walk got
    ops_ += kOpsPerPixelWalked * n;
    float inv_w = t.inv_w.at(x_begin - t.x_ref, y - t.y_ref);
    float* depth = &inv_depth_[size_t(y) * width_];
    p.y = y;
    p.row_start = x_begin;
    p.count = 0;
    for (int x = x_begin; x < x_end; ++x, inv_w += t.inv_w.ax) {
      if (inv_w > depth[x]) {
        depth[x] = inv_w;
        if (p.count == 0) p.x0 = x;
        p.inv_w[p.count] = inv_w;
        p.w[p.count] = 1.0f / inv_w;
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
