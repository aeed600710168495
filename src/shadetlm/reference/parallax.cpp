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

// q(s) = c0 + c1·s + c2·s², the ray's height above the relief over one cell, s = t − t_in
// from the ray's entry into the cell (expanded there, so that far along the ray the
// coefficients keep their precision).
struct Quadratic {
  double c0 = 0, c1 = 0, c2 = 0;
  double at(double s) const { return c0 + s * (c1 + s * c2); }
};

// Over cell (i, j) the relief is the bilinear patch of its four corner texels (each
// clamped to [0, 1], wrapping): h00 + B·a + C·b + E·a·b with a = x − i, b = y − j. Along
// the ray a and b are linear in s, so g − h is a quadratic.
Quadratic above_cell(const core::Texture& map, int i, int j, const Ray& r, double t_in) {
  auto h = [&](int x, int y) { return std::clamp(map.texel(x, y).r, 0.0, 1.0); };
  const double h00 = h(i, j), h10 = h(i + 1, j), h01 = h(i, j + 1), h11 = h(i + 1, j + 1);
  const double B = h10 - h00, C = h01 - h00, E = h00 - h10 - h01 + h11;
  const double a0 = r.x0 + t_in * r.ax - i, b0 = r.y0 + t_in * r.ay - j, g0 = 1 + t_in * r.dh;
  Quadratic q;
  q.c0 = g0 - (h00 + B * a0 + C * b0 + E * a0 * b0);
  q.c1 = r.dh - (B * r.ax + C * r.ay + E * (a0 * r.ay + b0 * r.ax));
  q.c2 = -E * r.ax * r.ay;
  return q;
}

// The roots of q in [0, len], ascending; a root that rounding put just outside (a ray
// meeting the relief on the cell's border) is taken, clamped into it.
std::vector<double> roots_in(const Quadratic& q, double len) {
  std::vector<double> out;
  const double slack = 1e-12 * (len + 1);
  auto take = [&](double s) {
    if (s >= -slack && s <= len + slack) out.push_back(std::clamp(s, 0.0, len));
  };
  const double scale = std::abs(q.c0) + std::abs(q.c1) * len + 1e-300;
  if (std::abs(q.c2) * len * len < 1e-14 * scale) {  // linear to rounding
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

// Over [0, len] of one cell: the first s where the ray is at or under the relief
// (q ≤ 0), or −1.
double first_under(const Quadratic& q, double len) {
  if (q.at(0) <= 0) return 0;
  const std::vector<double> roots = roots_in(q, len);
  if (!roots.empty()) return roots.front();
  return q.at(len) <= 0 ? len : -1;  // a root that rounding lost entirely: at the end
}

// Over [0, len], the ray at or under the relief at 0: the first s where it is above
// again (q > 0 just after), or −1.
double first_above(const Quadratic& q, double len) {
  std::vector<double> ends = roots_in(q, len);
  ends.push_back(len);
  double from = 0;
  for (double s : ends) {
    if (s > from && q.at(0.5 * (from + s)) > 0) return from;  // (an empty piece: a double root)
    from = s;
  }
  return -1;
}

// Walks the cells the ray crosses from t_start to t_end (a 2-D DDA), calling
// `cell(q, t_in, t_out)` for each until it returns true; at most `max_cells` of them.
template <class Visit>
void walk_cells(const core::Texture& map, const Ray& r, double t_start, double t_end, long max_cells, Visit&& cell) {
  const double inf = std::numeric_limits<double>::infinity();
  const double xs = r.x0 + t_start * r.ax, ys = r.y0 + t_start * r.ay;
  double i = std::floor(xs), j = std::floor(ys);
  if (r.ax < 0 && i == xs) i -= 1;  // on a border going back: the cell behind
  if (r.ay < 0 && j == ys) j -= 1;
  // Where the ray leaves the current cell's column, from the cell itself (not summed
  // steps, which stop advancing on long rays).
  auto leave = [inf](double k, double origin, double a) {
    return a > 0 ? (k + 1 - origin) / a : a < 0 ? (k - origin) / a : inf;
  };
  double t = t_start;
  for (long n = 0; t < t_end && n < max_cells; ++n) {
    const double tx = leave(i, r.x0, r.ax), ty = leave(j, r.y0, r.ay);
    const double out = std::max(t, std::min({tx, ty, t_end}));
    if (cell(above_cell(map, int(i), int(j), r, t), t, out)) return;
    t = out;
    if (tx <= ty) i += r.ax > 0 ? 1 : -1;
    else j += r.ay > 0 ? 1 : -1;
  }
}

}  // namespace

ParallaxHit parallax_hit(const core::Texture& map, glm::dvec2 uv0, glm::dvec3 d, double depth) {
  ParallaxHit hit;
  hit.uv = uv0;
  if (!(depth > 0) || !(d.z < 0) || !std::isfinite(d.x) || !std::isfinite(d.y)) return hit;
  const double W = map.width, H = map.height;
  const Ray r{uv0.x * W - 0.5, (1 - uv0.y) * H - 0.5, d.x * W, -d.y * H, d.z / depth};
  const double t_floor = -1 / r.dh;  // where the ray reaches h = 0, under every relief
  if (!std::isfinite(t_floor)) return hit;  // a slope that underflows: parallel to the surface
  hit.traced = true;
  // More cells than a ray of any scene here crosses (a 4096² map seen at 0.05°); a longer
  // one (a hostile depth or slope) ends where the walk stopped, taken as the floor.
  const long max_cells = 1L << 22;
  hit.t = t_floor;
  walk_cells(map, r, 0, t_floor, max_cells, [&](const Quadratic& q, double lo, double hi) {
    const double s = first_under(q, hi - lo);
    if (s >= 0) hit.t = lo + s;
    return s >= 0;
  });
  hit.uv = uv0 + hit.t * glm::dvec2(d.x, d.y);
  hit.height = std::clamp(1 + hit.t * r.dh, 0.0, 1.0);
  // Where the ray leaves the first solid piece again (or the floor).
  hit.t_exit = t_floor;
  walk_cells(map, r, hit.t, t_floor, max_cells, [&](const Quadratic& q, double lo, double hi) {
    const double s = first_above(q, hi - lo);
    if (s >= 0) hit.t_exit = std::max(hit.t, lo + s);
    return s >= 0;
  });
  return hit;
}

}  // namespace shadetlm::reference
