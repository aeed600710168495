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
//
// Under the DRAM model (docs/memory.md) the depth buffer (32 bits a pixel) lies in
// memory behind the raster's cache: every pixel walked reads its depth, a visible one
// writes it. The accesses are made in walk order as each packet is sent (and at each
// row's end), so that the walk's loops stay as they are.
#include <memory>
#include <optional>
#include <vector>

#include "shadetlm/tlm/packet.hpp"
#include "shadetlm/memory/cache.hpp"

namespace shadetlm::modules {

class RasterKernel {
 public:
  RasterKernel(int width, int height, std::optional<CacheConfig> cache = std::nullopt);

  // A hidden pixel whose depth read moved DRAM lines: its step in the frame's walk.
  struct HiddenLines {
    uint64_t step;
    uint16_t lines;
  };

  // Calls emit(SpanPacket&) for each run of visible pixels of the triangle.
  template <class Emit>
  void run(const TriangleSetup& t, Emit&& emit);

  const Ops& ops() const { return ops_; }
  uint64_t pixels_walked() const { return walked_; }
  uint64_t row_walked_before() const { return row_before_; }  // walked before this row
  uint64_t pixels_hidden() const { return hidden_; }
  // The visible pixels' depth traffic (DRAM lines) of the packet being sent.
  Work work() const { return {nullptr, 1, memory_ ? lines_ : nullptr}; }
  const MemoryClient* memory() const { return memory_.get(); }
  // The hidden pixels that moved lines, in walk order, since the caller last cleared it.
  std::vector<HiddenLines>& hidden_lines() { return hidden_lines_; }

  // Per pixel walked: the 1/w step (compares are free, as everywhere); per visible
  // pixel, the reciprocal; per seed (a row's first pixel, then every kSpanMax), the
  // plane evaluated.
  static constexpr Ops kOpsPerPixelWalked{/*add*/ 1};
  static constexpr Ops kOpsPerPixelVisible{0, 0, /*div*/ 1};
  static constexpr Ops kOpsPerSeed{/*add*/ 2, /*mul*/ 2};

 private:
  int width_, height_;
  std::vector<float> inv_depth_;
  SpanPacket packet_{};  // zeroed: the lanes past a packet's count are read (kLanes)
  Ops ops_;
  uint64_t walked_ = 0, hidden_ = 0, row_before_ = 0;
  // The depth buffer's memory traffic (none: ideal memory).
  std::unique_ptr<MemoryClient> memory_;
  Surface depth_surface_;
  uint16_t lines_[kSpanMax] = {};
  std::vector<HiddenLines> hidden_lines_;
  int accessed_to_ = 0;  // the row's pixels before it have made their accesses
  void access_hidden(int y, int x_begin, int until);
  void access_packet(const SpanPacket& p, int x_begin);
};

template <class Emit>
void RasterKernel::run(const TriangleSetup& t, Emit&& emit) {
  SpanPacket& p = packet_;
  p.tri = &t;
  // The walk's state in locals (the packet and the depth buffer are memory the compiler
  // cannot keep in registers across their stores).
  const float step = t.inv_w.ax, inv_w_min = t.inv_w_min;
  int count = 0;
  uint64_t hidden = 0;
  // Sends the run of visible pixels gathered: w = 1/(1/w) for the whole packet in one
  // loop (whole groups of lanes, kLanes; the lanes past the count divide what they hold).
  auto send = [&](int x_after) {  // x_after: one past the run's last pixel
    p.x0 = x_after - count;
    for (int i = 0; i < lanes(count); ++i) p.w[i] = 1.0f / p.inv_w[i];
    ops_ += kOpsPerPixelVisible * uint64_t(count);
    p.count = count;
    if (memory_) access_packet(p, p.row_start);
    emit(p);
    count = 0;
  };
  // From setup's reference row, the top covered one (packet.hpp): the rows above it are
  // empty, and setup has already found so.
  for (int y = t.y_ref; y <= t.coverage.y1; ++y) {
    const auto [x_begin, x_end] = t.coverage.row_span(y);
    if (x_begin >= x_end) continue;
    const uint64_t n = uint64_t(x_end - x_begin);
    row_before_ = walked_;
    walked_ += n;
    ops_ += kOpsPerPixelWalked * n + kOpsPerSeed * ((n + kSpanMax - 1) / kSpanMax);
    float* const depth = &inv_depth_[size_t(y) * width_];
    p.y = y;
    p.row_start = x_begin;
    accessed_to_ = x_begin;
    for (int seed = x_begin; seed < x_end; seed += kSpanMax) {  // re-seeded every kSpanMax pixels
      float inv_w = t.inv_w.at(seed - t.x_ref, y - t.y_ref);
      const int end = x_end - seed > kSpanMax ? seed + kSpanMax : x_end;
      int x = seed;
      while (x < end) {
        // Visible pixels join the run, up to a hidden one or a full packet: no call in
        // this loop, so that its state stays in registers.
        const int stop = end - x > kSpanMax - count ? x + kSpanMax - count : end;
        for (; x < stop; ++x, inv_w += step) {
          const float inv_w_pixel = inv_w > 0 ? inv_w : inv_w_min;
          if (!(inv_w_pixel > depth[x])) break;
          depth[x] = inv_w_pixel;
          p.inv_w[count++] = inv_w_pixel;
        }
        if (x < stop) {  // pixel x is hidden: it ends the run, and the hidden ones are passed
          if (count > 0) send(x);
          for (; x < end; ++x, inv_w += step, ++hidden) {
            const float inv_w_pixel = inv_w > 0 ? inv_w : inv_w_min;
            if (inv_w_pixel > depth[x]) break;
          }
        } else if (count == kSpanMax) {
          send(x);
        }
      }
    }
    if (count > 0) send(x_end);
    if (memory_) access_hidden(y, x_begin, x_end);
  }
  hidden_ += hidden;
}

}  // namespace shadetlm::modules
