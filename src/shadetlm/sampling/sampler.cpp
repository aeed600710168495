#include "shadetlm/sampling/sampler.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace shadetlm::modules {

const std::vector<std::string>& filter_names() {
  static const std::vector<std::string> names = {"nearest", "bilinear", "trilinear", "anisotropic", "ewa"};
  return names;
}

namespace {

// Texel coordinates (s, r) of (u, v) on a level of W × H texels, with the wrap mode
// applied as in core::Texture: s, r end within one texel of [0, W) × [0, H).
// Inlined: it runs for every probe of every pixel.
[[gnu::always_inline]] inline void texel_coordinates(const core::Texture& t, float u, float v, float& s, float& r) {
  const float W = float(t.width), H = float(t.height);
  // Whole periods off first, so that far coordinates (a large uv_repeat) stay exact
  // enough and their texel indices in int's range; hardware drops the integer bits.
  if (t.wrap == core::Wrap::Repeat) u -= std::floor(u), v -= std::floor(v);
  s = u * W - 0.5f, r = (1.0f - v) * H - 0.5f;
  if (t.wrap == core::Wrap::Repeat) {
    s -= W * std::floor(s / W);
    r -= H * std::floor(r / H);
    if (s >= W) s -= W;  // a tiny negative s rounds to exactly W
    if (r >= H) r -= H;
  } else {
    s = std::fmin(std::fmax(s, -1.0f), W);
    r = std::fmin(std::fmax(r, -1.0f), H);
  }
  if (!(s == s) || !(r == r)) s = r = 0;  // NaN uv (none reach here from the pipeline): texel 0
}

[[gnu::always_inline]] inline int wrap(int i, int n, core::Wrap w) {
  if (w == core::Wrap::Repeat) return i >= n ? i - n : i < 0 ? i + n : i;
  return std::clamp(i, 0, n - 1);
}

// Per probe: texel coordinates (2 mul, 3 add), fractions (2 add), four reads, three
// channels of three lerps (9 mul, 18 add).
constexpr Ops kOpsBilinear{/*add*/ 23, /*mul*/ 11, 0, 0, 0, 0, /*fetch*/ 4};
constexpr Ops kOpsNearest{/*add*/ 3, /*mul*/ 2, 0, 0, 0, 0, /*fetch*/ 1};
// Between two levels: the LOD's fraction (1 add), three lerps (3 mul, 6 add).
constexpr Ops kOpsLevelBlend{/*add*/ 7, /*mul*/ 3};

}  // namespace

void place(MipMap& map, MemoryClient& memory) {
  map.surfaces.clear();
  for (const core::Texture* t : map.levels) map.surfaces.push_back(memory.place(t->width, t->height, 4));
}

void Sampler::touch(int level, int x, int y) {
  if (memory_) return touch_memory(level, x, y);
  lines_.add((uint64_t(level) << 48) | (uint64_t(uint32_t(y) >> 2) << 24) | uint64_t(uint32_t(x) >> 2));
}

void Sampler::read_lines() {
  lines_.for_each([&](uint64_t line) { memory_->read_line(line); });
}

void Sampler::touch_memory(int level, int x, int y) {
  lines_.add(memory_->line_of(map_->surfaces[size_t(level)], x, y));
}

void Sampler::nearest(const core::Texture& t, int level, float u, float v, float out[3], Ops& ops) {
  float s, r;
  texel_coordinates(t, u, v, s, r);
  const int x = wrap(int(std::floor(s + 0.5f)), t.width, t.wrap), y = wrap(int(std::floor(r + 0.5f)), t.height, t.wrap);
  touch(level, x, y);
  const glm::vec4& c = t.texels[size_t(y) * size_t(t.width) + size_t(x)];
  out[0] = c[0], out[1] = c[1], out[2] = c[2];
  ops += kOpsNearest;
}

void Sampler::bilinear(const core::Texture& t, int level, float u, float v, float out[3], Ops& ops) {
  float s, r;
  texel_coordinates(t, u, v, s, r);
  const float fs = std::floor(s), fr = std::floor(r);
  const float a = s - fs, b = r - fr;
  const int x0 = wrap(int(fs), t.width, t.wrap), x1 = wrap(int(fs) + 1, t.width, t.wrap);
  const int y0 = wrap(int(fr), t.height, t.wrap), y1 = wrap(int(fr) + 1, t.height, t.wrap);
  touch(level, x0, y0), touch(level, x1, y0), touch(level, x0, y1), touch(level, x1, y1);
  const glm::vec4* row0 = &t.texels[size_t(y0) * size_t(t.width)];
  const glm::vec4* row1 = &t.texels[size_t(y1) * size_t(t.width)];
  const glm::vec4 t00 = row0[x0], t10 = row0[x1], t01 = row1[x0], t11 = row1[x1];
  for (int c = 0; c < 3; ++c) {
    const float top = t00[c] + (t10[c] - t00[c]) * a;
    const float bottom = t01[c] + (t11[c] - t01[c]) * a;
    out[c] = top + (bottom - top) * b;
  }
  ops += kOpsBilinear;
}

void Sampler::trilinear(const MipMap& map, float lod, float u, float v, float out[3], Ops& ops) {
  const int last = int(map.levels.size()) - 1;
  const int l0 = std::min(int(lod), last);
  bilinear(*map.levels[size_t(l0)], l0, u, v, out, ops);
  const float f = lod - float(l0);
  if (l0 == last || f <= 0) return;  // on a level: one probe
  float upper[3];
  bilinear(*map.levels[size_t(l0) + 1], l0 + 1, u, v, upper, ops);
  for (int c = 0; c < 3; ++c) out[c] += (upper[c] - out[c]) * f;
  ops += kOpsLevelBlend;
}

void Sampler::ewa(const MipMap& map, float u, float v, float ax, float ay, float bx, float by, float out[3],
                  Ops& ops) {
  // The ellipse inscribed in the pixel's footprint: the half-axes are half the uv
  // derivatives (the pixel spans ±½ around its centre), in texel coordinates of level 0
  // (s right, r down: r runs against v). Its matrix M = J·Jᵀ (J the half-axes as
  // columns): the points x with xᵀ M⁻¹ x < 1.
  ax *= 0.5f, bx *= 0.5f, ay *= -0.5f, by *= -0.5f;
  float p = ax * ax + bx * bx, q = ax * ay + bx * by, r = ay * ay + by * by;
  // The true axes are M's eigenvalues: major² = λ1, minor² = λ2. At most 16 : 1, by
  // widening (M + c·I) — else a long ellipse would read a very fine level.
  const float mean = 0.5f * (p + r), dev = std::sqrt(0.25f * (p - r) * (p - r) + q * q);
  const float major2 = mean + dev;
  float minor2 = mean - dev;
  constexpr float kMaxEccentricity2 = 16 * 16;
  if (minor2 * kMaxEccentricity2 < major2) {
    const float widen = major2 / kMaxEccentricity2 - minor2;
    p += widen, r += widen, minor2 += widen;
  }
  const int last = int(map.levels.size()) - 1;
  const float minor_lod = minor2 > 1.0f ? 0.5f * std::log2(minor2) : 0.0f;
  const int level = std::isfinite(minor_lod) ? std::min(int(minor_lod), last) : last;
  lod_ = float(level);
  const core::Texture& t = *map.levels[size_t(level)];
  const core::Texture& base = *map.levels.front();
  // To the level's texels, axis by axis (a non-square texture's short side stops at 1).
  const float ks = float(t.width) / float(base.width), kr = float(t.height) / float(base.height);
  p *= ks * ks, q *= ks * kr, r *= kr * kr;
  // Widened by a unit reconstruction filter (Heckbert's +1), then the quadratic form of
  // M⁻¹: A s² + B s r + C r² < 1.
  p += 1, r += 1;
  const float det = p * r - q * q;
  const float A = r / det, B = -2 * q / det, C = p / det;
  // The ellipse's bounding box, no larger than the level (at the coarsest level a huge
  // footprint covers the whole texture, and every texel once is enough).
  const float half_s = std::min(std::sqrt(p), float(t.width)), half_r = std::min(std::sqrt(r), float(t.height));
  float s0, r0;
  texel_coordinates(t, u, v, s0, r0);
  ops += Ops{/*add*/ 14, /*mul*/ 26, /*div*/ 5, /*sqrt*/ 3, 0, /*lut*/ 1};
  float sum[3] = {0, 0, 0}, weights = 0;
  const int x_lo = int(std::ceil(s0 - half_s)), x_hi = int(std::floor(s0 + half_s));
  const int y_lo = int(std::ceil(r0 - half_r)), y_hi = int(std::floor(r0 + half_r));
  for (int y = y_lo; y <= y_hi; ++y)
    for (int x = x_lo; x <= x_hi; ++x) {
      const float ds = float(x) - s0, dr = float(y) - r0;
      const float r2 = A * ds * ds + B * ds * dr + C * dr * dr;
      ops += Ops{/*add*/ 4, /*mul*/ 5};
      if (r2 >= 1) continue;
      const float w = std::exp(-2.0f * r2);  // a Gaussian of the elliptical radius (one table look-up)
      int tx = x % t.width, ty = y % t.height;
      if (t.wrap == core::Wrap::Repeat) tx += tx < 0 ? t.width : 0, ty += ty < 0 ? t.height : 0;
      else tx = std::clamp(x, 0, t.width - 1), ty = std::clamp(y, 0, t.height - 1);
      touch(level, tx, ty);
      const glm::vec4& c = t.texels[size_t(ty) * size_t(t.width) + size_t(tx)];
      for (int k = 0; k < 3; ++k) sum[k] += w * c[k];
      weights += w;
      ops += Ops{/*add*/ 4, /*mul*/ 3, 0, 0, 0, /*lut*/ 1, /*fetch*/ 1};
    }
  if (weights > 0) {
    for (int k = 0; k < 3; ++k) out[k] = sum[k] / weights;
    ops += Ops{0, 0, /*div*/ 3};
  } else {  // no texel centre inside (cannot happen with the +1): bilinear
    bilinear(t, level, u, v, out, ops);
  }
}

void Sampler::sample(const MipMap& map, float u, float v, float dudx, float dvdx, float dudy, float dvdy,
                     float out[3], Ops& ops) {
  lines_.clear();
  map_ = &map;
  const uint64_t fetches_before = ops.fetch;
  const core::Texture& base = *map.levels.front();
  const float W = float(base.width), H = float(base.height);
  // The footprint's axes in texels of the finest level (4 mul), their squared lengths
  // (4 mul, 2 add); the LOD is half the log2 of a squared length (1 lut, 1 mul).
  const float ax = dudx * W, ay = dvdx * H, bx = dudy * W, by = dvdy * H;
  const float a2 = ax * ax + ay * ay, b2 = bx * bx + by * by;
  ops += Ops{/*add*/ 2, /*mul*/ 9, 0, 0, 0, /*lut*/ 1};
  const float last = float(map.levels.size() - 1);
  auto lod_of = [&](float squared) {
    const float l = squared > 1.0f ? 0.5f * std::log2(squared) : 0.0f;
    return std::isfinite(l) ? std::min(l, last) : last;  // clamped to the chain
  };
  if (filter_ == Filter::Ewa) {
    ewa(map, u, v, ax, ay, bx, by, out, ops);
  } else if (filter_ == Filter::Anisotropic) {
    // Probes along the major axis, spaced by its length over N; the level of that
    // spacing, but never finer than the minor axis (1 mul for the N², 2 mul per step).
    // As many probes as the footprint's anisotropy asks, up to `probes`: N = ⌈major/minor⌉.
    const bool a_major = a2 >= b2;
    const float major2 = a_major ? a2 : b2, minor2 = a_major ? b2 : a2;
    const float ratio = minor2 > 0 ? std::sqrt(major2 / minor2) : float(probes_);
    const int count = std::isfinite(ratio) ? std::clamp(int(std::ceil(ratio - 1e-3f)), 1, probes_) : probes_;
    const float n = float(count);
    lod_ = lod_of(std::max(minor2, major2 / (n * n)));
    const float du = (a_major ? dudx : dudy) / n, dv = (a_major ? dvdx : dvdy) / n;
    ops += Ops{/*add*/ 1, /*mul*/ 1, /*div*/ 2, /*sqrt*/ 1};  // the ratio, N², major²/N²
    ops.mul += 2;                                          // the step: 2 mul by 1/N (a table)
    float sum[3] = {0, 0, 0};
    for (int k = 0; k < count; ++k) {
      const float offset = float(k) + 0.5f - 0.5f * n;  // centred on the pixel
      float probe[3];
      trilinear(map, lod_, u + du * offset, v + dv * offset, probe, ops);
      for (int c = 0; c < 3; ++c) sum[c] += probe[c];
      ops += Ops{/*add*/ 5, /*mul*/ 2};  // the probe's position, the sum
    }
    for (int c = 0; c < 3; ++c) out[c] = sum[c] / n;
    ops += Ops{0, /*mul*/ 3};  // by 1/N
  } else {
    lod_ = lod_of(std::max(a2, b2));
    if (filter_ == Filter::Trilinear) {
      trilinear(map, lod_, u, v, out, ops);
    } else {
      const int level = std::min(int(lod_ + 0.5f), int(last));  // the nearest level
      if (filter_ == Filter::Bilinear) bilinear(*map.levels[size_t(level)], level, u, v, out, ops);
      else nearest(*map.levels[size_t(level)], level, u, v, out, ops);
    }
  }
  ops.line += uint64_t(lines_.size());
  if (memory_) read_lines();
  cycles_ += std::max<uint64_t>(1, (ops.fetch - fetches_before + 3) / 4);
}

}  // namespace shadetlm::modules

namespace shadetlm::modules {

void sample_span(const TriangleSetup& t, const SpanPacket& p, const MipMap& map, Sampler& sampler,
                 float out[3][kSpanMax], Ops& ops, ValueRange& uv_range, uint16_t cycles[kSpanMax],
                 float (*uv_lod)[kSpanMax], uint16_t* lines) {
  const int dx = p.x0 - t.x_ref, dy = p.y - t.y_ref;
  float u_w = t.uv[0].at(dx, dy), v_w = t.uv[1].at(dx, dy);
  uv_range.add_span(u_w, t.uv[0].ax, p.count, p.w);
  uv_range.add_span(v_w, t.uv[1].ax, p.count, p.w);
  for (int i = 0; i < p.count; ++i) {
    const float w = p.w[i];
    const float u = u_w * w, v = v_w * w;
    const float dudx = (t.uv[0].ax - u * t.inv_w.ax) * w, dvdx = (t.uv[1].ax - v * t.inv_w.ax) * w;
    const float dudy = (t.uv[0].ay - u * t.inv_w.ay) * w, dvdy = (t.uv[1].ay - v * t.inv_w.ay) * w;
    u_w += t.uv[0].ax, v_w += t.uv[1].ax;
    float value[3];
    const uint64_t before = sampler.cycles();
    sampler.sample(map, u, v, dudx, dvdx, dudy, dvdy, value, ops);
    cycles[i] = uint16_t(std::min<uint64_t>(sampler.cycles() - before, 65535));
    if (lines) lines[i] = sampler.memory()->take_pixel_lines();
    for (int c = 0; c < 3; ++c) out[c][i] = value[c];
    if (uv_lod) uv_lod[0][i] = u, uv_lod[1][i] = v, uv_lod[2][i] = sampler.last_lod();
  }
  ops += kOpsSpanUvPerPixel * uint64_t(p.count);
  if (p.count > 0) ops += kOpsSpanUvPerSpan;
}

}  // namespace shadetlm::modules
