#include "shadetlm/reference/parallax.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace shadetlm::reference {

namespace {

// The ray in the map's texel space (texel centres at integers, rows down):
// x(t) = x0 + t·ax, y(t) = y0 + t·ay, its height g(t) = 1 + t·dh.
struct Ray {
  double x0, y0, ax, ay, dh;
};

// q(t) = c0 + c1·t + c2·t², the ray's height above the relief over one cell.
struct Quadratic {
  double c0 = 0, c1 = 0, c2 = 0;
  double at(double t) const { return c0 + t * (c1 + t * c2); }
};

// Over cell (i, j) the relief is the bilinear patch of its four corner texels (each
// clamped to [0, 1], wrapping): h00 + B·a + C·b + E·a·b with a = x − i, b = y − j. Along
// the ray a and b are linear in t, so g − h is a quadratic.
Quadratic above_cell(const core::Texture& map, int i, int j, const Ray& r) {
  auto h = [&](int x, int y) { return std::clamp(map.texel(x, y).r, 0.0, 1.0); };
  const double h00 = h(i, j), h10 = h(i + 1, j), h01 = h(i, j + 1), h11 = h(i + 1, j + 1);
  const double B = h10 - h00, C = h01 - h00, E = h00 - h10 - h01 + h11;
  const double a0 = r.x0 - i, b0 = r.y0 - j;
  Quadratic q;
  q.c0 = 1 - (h00 + B * a0 + C * b0 + E * a0 * b0);
  q.c1 = r.dh - (B * r.ax + C * r.ay + E * (a0 * r.ay + b0 * r.ax));
  q.c2 = -E * r.ax * r.ay;
  return q;
}

// The roots of q in [lo, hi], ascending (a double root once).
std::vector<double> roots_in(const Quadratic& q, double lo, double hi) {
  std::vector<double> out;
  auto take = [&](double t) {
    if (t >= lo && t <= hi) out.push_back(t);
  };
  const double scale = std::abs(q.c0) + std::abs(q.c1) * std::max(std::abs(lo), std::abs(hi)) + 1e-300;
  if (std::abs(q.c2) * hi * hi < 1e-14 * scale) {  // linear to rounding
    if (q.c1 != 0) take(-q.c0 / q.c1);
  } else {
    const double disc = q.c1 * q.c1 - 4 * q.c2 * q.c0;
    if (disc >= 0) {  // the stable pair: p = −½(c1 + sign(c1)·√disc), roots p/c2 and c0/p
      const double p = -0.5 * (q.c1 + std::copysign(std::sqrt(disc), q.c1));
      take(p / q.c2);
      if (p != 0) take(q.c0 / p);
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Over [lo, hi] of one cell: the first t where the ray is at or under the relief (q ≤ 0),
// or −1.
double first_under(const Quadratic& q, double lo, double hi) {
  if (q.at(lo) <= 0) return lo;
  const std::vector<double> roots = roots_in(q, lo, hi);
  if (!roots.empty()) return roots.front();
  return q.at(hi) <= 0 ? hi : -1;  // a root that rounding moved just past the end
}

// Over [lo, hi], the ray at or under the relief at lo: the first t where it is above
// again (q > 0 just after), or −1.
double first_above(const Quadratic& q, double lo, double hi) {
  std::vector<double> roots = roots_in(q, lo, hi);
  roots.push_back(hi);
  double from = lo;
  for (double t : roots) {
    if (t > from && q.at(0.5 * (from + t)) > 0) return from;  // (an empty piece: the hit's own root)
    from = t;
  }
  return -1;
}

// Walks the cells the ray crosses from t = 0 to t_end (a 2-D DDA), calling
// `cell(q, t_in, t_out)` for each until it returns true.
template <class Visit>
void walk_cells(const core::Texture& map, const Ray& r, double t_start, double t_end, Visit&& cell) {
  const double inf = std::numeric_limits<double>::infinity();
  const double xs = r.x0 + t_start * r.ax, ys = r.y0 + t_start * r.ay;
  double i = std::floor(xs), j = std::floor(ys);
  if (r.ax < 0 && i == xs) i -= 1;  // on a border going back: the cell behind
  if (r.ay < 0 && j == ys) j -= 1;
  double tx = r.ax > 0 ? (i + 1 - r.x0) / r.ax : r.ax < 0 ? (i - r.x0) / r.ax : inf;
  double ty = r.ay > 0 ? (j + 1 - r.y0) / r.ay : r.ay < 0 ? (j - r.y0) / r.ay : inf;
  double t = t_start;
  while (t < t_end) {
    const double out = std::min({tx, ty, t_end});
    if (cell(above_cell(map, int(i), int(j), r), t, out)) return;
    t = out;
    if (tx <= ty) i += r.ax > 0 ? 1 : -1, tx += 1 / std::abs(r.ax);
    else j += r.ay > 0 ? 1 : -1, ty += 1 / std::abs(r.ay);
  }
}

}  // namespace

ParallaxHit parallax_hit(const core::Texture& map, glm::dvec2 uv0, glm::dvec3 d, double depth) {
  ParallaxHit hit;
  hit.uv = uv0;
  if (!(depth > 0) || !(d.z < 0) || !std::isfinite(d.x) || !std::isfinite(d.y)) return hit;
  hit.traced = true;
  const double W = map.width, H = map.height;
  const Ray r{uv0.x * W - 0.5, (1 - uv0.y) * H - 0.5, d.x * W, -d.y * H, d.z / depth};
  const double t_floor = -1 / r.dh;  // where the ray reaches h = 0, under every relief
  hit.t = t_floor;
  walk_cells(map, r, 0, t_floor, [&](const Quadratic& q, double lo, double hi) {
    const double t = first_under(q, lo, hi);
    if (t >= 0) hit.t = t;
    return t >= 0;
  });
  hit.uv = uv0 + hit.t * glm::dvec2(d.x, d.y);
  hit.height = std::clamp(1 + hit.t * r.dh, 0.0, 1.0);
  // Where the ray leaves the first solid piece again (or the floor).
  hit.t_exit = t_floor;
  walk_cells(map, r, hit.t, t_floor, [&](const Quadratic& q, double lo, double hi) {
    const double t = first_above(q, lo, hi);
    if (t >= 0) hit.t_exit = t;
    return t >= 0;
  });
  return hit;
}

}  // namespace shadetlm::reference
