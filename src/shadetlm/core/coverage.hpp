#pragma once
// The coverage convention, shared by the golden model and the pipeline so that which
// pixels a triangle covers is never a source of difference between them:
//
//  * clip space is OpenGL's; triangles are clipped against the near and far planes
//    and a guard band |x|, |y| ≤ 8·w (bounds the fixed-point range), in double;
//  * screen space has x to the right and y down; pixel (px, py) is the square
//    [px, px+1) × [py, py+1) with its centre at (px + ½, py + ½);
//  * vertices are snapped to a grid of 1/256 pixel (8 fractional bits), as hardware
//    does, and edge functions are evaluated exactly in 64-bit integers;
//  * a pixel is covered when its centre is inside the triangle, or on a top or left
//    edge (the top-left fill rule), so that triangles sharing an edge cover each pixel
//    along it exactly once.
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace shadetlm::core {

constexpr int kSubpixelBits = 8;
constexpr int64_t kSubpixelScale = int64_t(1) << kSubpixelBits;
constexpr double kGuardBand = 8.0;

struct ClipVertex {
  glm::dvec4 clip;   // clip-space position
  glm::dvec3 bary;   // its weights on the original triangle's three vertices
};

// A clipped triangle: each of the six planes adds at most one vertex, so at most 9.
// Fixed storage: clipping runs once per triangle and must not allocate.
struct ClipPolygon {
  std::array<ClipVertex, 9> vertices;
  size_t count = 0;
  size_t size() const { return count; }
  bool empty() const { return count == 0; }
  const ClipVertex& operator[](size_t i) const { return vertices[i]; }
  const ClipVertex* begin() const { return vertices.data(); }
  const ClipVertex* end() const { return vertices.data() + count; }
};

// The polygon left of triangle (c0, c1, c2) after clipping: empty, or 3 to 9
// vertices in the triangle's winding. Fan it as (0, i, i+1).
ClipPolygon clip_triangle(const glm::dvec4& c0, const glm::dvec4& c1, const glm::dvec4& c2);

// Clip space → screen: (x, y) in pixels, z = z_ndc.
glm::dvec3 to_screen(const glm::dvec4& clip, int width, int height);

struct SnappedTriangle {
  std::array<int64_t, 3> x, y;  // vertices in 1/256 pixel, ordered so that the edge
                                // functions are positive inside
  std::array<int, 3> source;    // which input vertex each one is
  bool front_facing = true;     // counter-clockwise on screen with y up
  int x0, y0, x1, y1;           // covered pixels lie in [x0, x1] × [y0, y1]

  // Edge function k (edge from vertex k to k+1) at the centre of pixel (px, py).
  int64_t edge(int k, int px, int py) const;
  bool covers(int px, int py) const;
  // The covered pixels of row py: [begin, end), begin == end when none.
  std::pair<int, int> row_span(int py) const;

 private:
  friend bool snap_triangle(const glm::dvec2&, const glm::dvec2&, const glm::dvec2&, int, int, SnappedTriangle&);
  // Edge k's test along a row, from its edge function and fill rule, set by
  // snap_triangle so that row_span does one multiply-add and one division per edge:
  // pixel px of row py passes when slope·px + step·py + offset ≥ 0.
  struct RowTest {
    int64_t slope, step, offset;
  };
  std::array<RowTest, 3> row_tests_;
  bool top_left(int k) const {
    const int n = (k + 1) % 3;
    const int64_t dx = x[n] - x[k], dy = y[n] - y[k];
    return dy < 0 || (dy == 0 && dx > 0);  // left edge, or horizontal top edge
  }
};

// v rounded to the nearest integer, halves away from zero: std::llround, without its
// call where |v| < 2⁶² (snapping rounds six coordinates per triangle).
inline int64_t round_half_away(double v) {
  if (!(std::fabs(v) < 0x1p62)) return std::llround(v);  // also NaN and infinities
  const int64_t truncated = int64_t(v);
  const double fraction = v - double(truncated);  // exact: v and its truncation share their leading bits
  return truncated + (fraction >= 0.5) - (fraction <= -0.5);
}

// Snaps a screen-space triangle (pixels) for a width × height viewport. Returns false
// when the snapped triangle has zero area or covers no pixel centre of the viewport's
// bounding box.
bool snap_triangle(const glm::dvec2& s0, const glm::dvec2& s1, const glm::dvec2& s2, int width,
                   int height, SnappedTriangle& out);

}  // namespace shadetlm::core
