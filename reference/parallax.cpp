#include "shadetlm/reference/parallax.hpp"

#include <algorithm>
#include <cmath>

namespace shadetlm::reference {

namespace {

// The height: texels clamped to [0, 1] first, then bilinear (texel centres, wrapping).
double relief(const core::Texture& map, glm::dvec2 uv) {
  const double s = uv.x * map.width - 0.5, r = (1 - uv.y) * map.height - 0.5;
  const double fs = std::floor(s), fr = std::floor(r);
  const int x = int(fs - map.width * std::floor(fs / map.width)), y = int(fr - map.height * std::floor(fr / map.height));
  auto h = [&](int i, int j) { return std::clamp(map.texel(i, j).r, 0.0, 1.0); };
  const double a = s - fs, b = r - fr;
  return (h(x, y) * (1 - a) + h(x + 1, y) * a) * (1 - b) + (h(x, y + 1) * (1 - a) + h(x + 1, y + 1) * a) * b;
}

}  // namespace

ParallaxHit parallax_hit(const core::Texture& map, glm::dvec2 uv0, glm::dvec3 d, double depth) {
  ParallaxHit r;
  r.uv = uv0;
  if (!(depth > 0) || !(d.z < 0) || !std::isfinite(d.x) || !std::isfinite(d.y)) return r;
  r.traced = true;
  const double W = map.width, H = map.height;
  const double dh = d.z / depth;  // height units per unit of t
  // The ray's height above the relief at t (negative: inside).
  auto above = [&](double t) { return 1 + t * dh - relief(map, uv0 + t * glm::dvec2(d.x, d.y)); };
  const double t_floor = -1 / dh;
  // Steps: at most 1/8 texel across and 1/512 of the depth down.
  const double across = std::max(std::abs(d.x) * W, std::abs(d.y) * H);
  const double dt = std::min(across > 0 ? 0.125 / across : t_floor, -1 / (512 * dh));
  auto bisect = [&](double lo, double hi, bool inside_at_hi) {
    while ((hi - lo) * std::max(across, 1e-300) > 1e-9 && (hi - lo) > 1e-15 * std::max(1.0, hi)) {
      const double mid = 0.5 * (lo + hi);
      if ((above(mid) <= 0) == inside_at_hi) hi = mid;
      else lo = mid;
    }
    return hi;
  };
  if (above(0) <= 0) {
    r.t = 0;
  } else {
    double t = 0;
    r.t = t_floor;
    while (t < t_floor) {
      const double next = std::min(t + dt, t_floor);
      if (above(next) <= 0) {
        r.t = bisect(t, next, true);
        break;
      }
      t = next;
    }
  }
  r.uv = uv0 + r.t * glm::dvec2(d.x, d.y);
  r.height = std::clamp(1 + r.t * dh, 0.0, 1.0);
  // The exit of the first solid piece: the march goes on until the ray is above again.
  r.t_exit = t_floor;
  for (double t = r.t; t < t_floor;) {
    const double next = std::min(t + dt, t_floor);
    if (above(next) > 0) {
      r.t_exit = bisect(t, next, false);
      break;
    }
    t = next;
  }
  return r;
}

}  // namespace shadetlm::reference
