#include "shadetlm/core/coverage.hpp"

#include <algorithm>
#include <cmath>

namespace shadetlm::core {

namespace {
// Signed distances of a clip-space point to the six clipping planes (inside ≥ 0).
double plane_distance(const glm::dvec4& p, int plane) {
  switch (plane) {
    case 0: return p.z + p.w;                 // near
    case 1: return p.w - p.z;                 // far
    case 2: return kGuardBand * p.w - p.x;
    case 3: return kGuardBand * p.w + p.x;
    case 4: return kGuardBand * p.w - p.y;
    default: return kGuardBand * p.w + p.y;
  }
}

int64_t floor_div(int64_t a, int64_t b) {  // b > 0
  const int64_t q = a / b;   // rounded towards zero
  return q - (a - q * b < 0);  // one less where a < 0 left a remainder
}
int64_t ceil_div(int64_t a, int64_t b) { return -floor_div(-a, b); }
}  // namespace

ClipPolygon clip_triangle(const glm::dvec4& c0, const glm::dvec4& c1, const glm::dvec4& c2) {
  ClipPolygon poly;
  for (const glm::dvec4* c : {&c0, &c1, &c2})
    for (int k = 0; k < 4; ++k)
      if (!std::isfinite((*c)[k])) return poly;  // nothing sensible to draw
  poly.vertices[0] = {c0, {1, 0, 0}};
  poly.vertices[1] = {c1, {0, 1, 0}};
  poly.vertices[2] = {c2, {0, 0, 1}};
  poly.count = 3;
  // Most triangles are inside every plane: nothing to cut. (Every test is made, with no
  // early exit: the compiler unrolls the loops and folds plane_distance's switch away.)
  bool inside = true;
  for (const glm::dvec4* c : {&c0, &c1, &c2})
    for (int plane = 0; plane < 6; ++plane) inside &= plane_distance(*c, plane) >= 0;
  if (inside) return poly;
  ClipPolygon next;
  for (int plane = 0; plane < 6 && !poly.empty(); ++plane) {
    next.count = 0;
    for (size_t i = 0; i < poly.size(); ++i) {  // Sutherland–Hodgman
      const ClipVertex& a = poly[i];
      const ClipVertex& b = poly[(i + 1) % poly.size()];
      const double da = plane_distance(a.clip, plane), db = plane_distance(b.clip, plane);
      if (da >= 0) next.vertices[next.count++] = a;
      if ((da >= 0) != (db >= 0)) {
        // Always from the inside vertex towards the outside one, so that an edge
        // shared by two triangles (walked a→b in one, b→a in the other) is cut at
        // bitwise the same point.
        const ClipVertex& in = da >= 0 ? a : b;
        const ClipVertex& out = da >= 0 ? b : a;
        const double din = da >= 0 ? da : db, dout = da >= 0 ? db : da;
        const double t = din / (din - dout);
        next.vertices[next.count++] = {in.clip + (out.clip - in.clip) * t, in.bary + (out.bary - in.bary) * t};
      }
    }
    poly = next;
  }
  if (poly.size() < 3) poly.count = 0;
  return poly;
}

glm::dvec3 to_screen(const glm::dvec4& c, int width, int height) {
  return {(c.x / c.w * 0.5 + 0.5) * width, (0.5 - c.y / c.w * 0.5) * height, c.z / c.w};
}

int64_t SnappedTriangle::edge(int k, int px, int py) const {
  const int n = (k + 1) % 3;
  const int64_t cx = int64_t(px) * kSubpixelScale + kSubpixelScale / 2;
  const int64_t cy = int64_t(py) * kSubpixelScale + kSubpixelScale / 2;
  return (x[n] - x[k]) * (cy - y[k]) - (y[n] - y[k]) * (cx - x[k]);
}

bool SnappedTriangle::covers(int px, int py) const {
  for (int k = 0; k < 3; ++k) {
    const int64_t e = edge(k, px, py);
    if (e < 0 || (e == 0 && !top_left(k))) return false;
  }
  return true;
}

std::pair<int, int> SnappedTriangle::row_span(int py) const {
  int64_t lo = x0, hi = x1;
  for (const RowTest& e : row_tests_) {
    const int64_t t = e.step * py + e.offset;  // the edge passes pixel px when slope·px + t ≥ 0
    if (e.slope > 0)
      lo = std::max(lo, -floor_div(t, e.slope));  // px ≥ ⌈−t / slope⌉
    else if (e.slope < 0)
      hi = std::min(hi, floor_div(t, -e.slope));  // px ≤ ⌊t / −slope⌋
    else if (t < 0)
      return {x0, x0};  // parallel to the row, and the row is outside it
  }
  if (lo > hi) return {x0, x0};
  return {int(lo), int(hi) + 1};
}

bool snap_triangle(const glm::dvec2& s0, const glm::dvec2& s1, const glm::dvec2& s2, int width,
                   int height, SnappedTriangle& t) {
  const glm::dvec2 s[3] = {s0, s1, s2};
  for (int k = 0; k < 3; ++k) {
    t.x[k] = round_half_away(s[k].x * kSubpixelScale);
    t.y[k] = round_half_away(s[k].y * kSubpixelScale);
    t.source[k] = k;
  }
  const int64_t area2 = (t.x[1] - t.x[0]) * (t.y[2] - t.y[0]) - (t.x[2] - t.x[0]) * (t.y[1] - t.y[0]);
  if (area2 == 0) return false;
  // With y down, counter-clockwise as seen on screen (y up) gives a negative area.
  t.front_facing = area2 < 0;
  if (area2 < 0) {
    std::swap(t.x[1], t.x[2]);
    std::swap(t.y[1], t.y[2]);
    std::swap(t.source[1], t.source[2]);
  }
  // Pixel centres px + ½ inside [min, max] of the vertices: px ≥ ceil(min − ½).
  const int64_t mnx = std::min({t.x[0], t.x[1], t.x[2]}), mxx = std::max({t.x[0], t.x[1], t.x[2]});
  const int64_t mny = std::min({t.y[0], t.y[1], t.y[2]}), mxy = std::max({t.y[0], t.y[1], t.y[2]});
  const int64_t half = kSubpixelScale / 2;
  t.x0 = int(std::max<int64_t>(0, ceil_div(mnx - half, kSubpixelScale)));
  t.y0 = int(std::max<int64_t>(0, ceil_div(mny - half, kSubpixelScale)));
  t.x1 = int(std::min<int64_t>(width - 1, floor_div(mxx - half, kSubpixelScale)));
  t.y1 = int(std::min<int64_t>(height - 1, floor_div(mxy - half, kSubpixelScale)));
  if (!(t.x0 <= t.x1 && t.y0 <= t.y1)) return false;
  // Edge function k at the centre (cx, cy) of pixel (px, py), cx = 256·px + ½·256:
  //   (x[n] − x[k])(cy − y[k]) − (y[n] − y[k])(cx − x[k]) ≥ need,
  // need = 0 on a top or left edge, 1 elsewhere, linear in px and py.
  for (int k = 0; k < 3; ++k) {
    const int n = (k + 1) % 3;
    const int64_t dx = t.x[n] - t.x[k], dy = t.y[n] - t.y[k];
    t.row_tests_[k] = {-dy * kSubpixelScale, dx * kSubpixelScale,
                       dx * (half - t.y[k]) - dy * (half - t.x[k]) - (t.top_left(k) ? 0 : 1)};
  }
  return true;
}

}  // namespace shadetlm::core
