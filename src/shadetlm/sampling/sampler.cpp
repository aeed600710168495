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
// applied as in core::Texture: s, r end within one texel of [0, W) × [0, H). Dropping
// whole periods and clamping are wiring (done on the value, not counted): for
// power-of-two sizes; another size's period would take a modulo unit, not counted either.
// (u·W is counted as a product: a texture need not be a power of two wide.)
// Inlined: it runs for every probe of every pixel.
template <class T>
[[gnu::always_inline]] inline void texel_coordinates(const core::Texture& t, T u, T v, T& s, T& r) {
  const float W = float(t.width), H = float(t.height);
  // Whole periods off first, so that far coordinates (a large uv_repeat) stay exact
  // enough and their texel indices in int's range; hardware drops the integer bits.
  if (t.wrap == core::Wrap::Repeat) u = T(value(u) - std::floor(value(u))), v = T(value(v) - std::floor(value(v)));
  s = u * W - 0.5f, r = (1.0f - v) * H - 0.5f;
  float sv = value(s), rv = value(r);
  if (t.wrap == core::Wrap::Repeat) {
    sv -= W * std::floor(sv / W);
    rv -= H * std::floor(rv / H);
    if (sv >= W) sv -= W;  // a tiny negative s rounds to exactly W
    if (rv >= H) rv -= H;
  } else {
    sv = std::fmin(std::fmax(sv, -1.0f), W);
    rv = std::fmin(std::fmax(rv, -1.0f), H);
  }
  if (!(sv == sv) || !(rv == rv)) sv = rv = 0;  // NaN uv (none reach here from the pipeline): texel 0
  s = T(sv), r = T(rv);
}

[[gnu::always_inline]] inline int wrap(int i, int n, core::Wrap w) {
  if (w == core::Wrap::Repeat) return i >= n ? i - n : i < 0 ? i + n : i;
  return std::clamp(i, 0, n - 1);
}

// x / n for the anisotropic filter's whole number of probes n: times 1/n from a table in
// hardware (one multiplication, as counted); the model divides, as it always has.
template <class T> T over_probes(T x, float n) {
  if constexpr (is_counted<T>::value) {
    ++T::ops.mul;
    return value(x) / n;
  } else {
    return x / n;
  }
}

// The level of detail of a squared footprint length, half its log2 (1 lut; the half a
// shift; below one texel, level 0: log2 of 1), clamped to the chain.
template <class T> T lod_of(T squared, float last, Ops& ops) {
  ops += Ops{0, 0, 0, 0, 0, /*lut*/ 1};
  const T l = shifted(log2_op(std::max(T(1.0f), squared)), T(0.5f));  // max(1, NaN) is 1: level 0
  return std::isfinite(value(l)) ? std::min(l, T(last)) : T(last);
}

// Per probe: texel coordinates (2 mul, 3 add), fractions (2 add), four reads, three
// channels of three lerps (9 mul, 18 add).
constexpr Ops kOpsBilinear{/*add*/ 23, /*mul*/ 11, 0, 0, 0, 0, /*fetch*/ 4};
constexpr Ops kOpsNearest{/*add*/ 3, /*mul*/ 2, 0, 0, 0, 0, /*fetch*/ 1};
// Between two levels: the LOD's fraction (1 add), three lerps (3 mul, 6 add).
constexpr Ops kOpsLevelBlend{/*add*/ 7, /*mul*/ 3};
// EWA's ellipse, before its texels (besides the footprint's axes and the LOD): the
// half-axes (shifts), M (6 mul, 3 add), its eigenvalues (2 mul, 5 add, 1 sqrt), the
// widening (4 add), the level's scale (3 mul), the filter's +1 (2 add), M⁻¹ (2 mul,
// 1 add, 3 div), the box (2 sqrt, 4 add), the centre's texel coordinates (2 mul, 3 add).
constexpr Ops kOpsEwaSetup{/*add*/ 22, /*mul*/ 15, /*div*/ 3, /*sqrt*/ 3};
// Per texel of its box: the radius test (2 add for the offsets, A ds² + B ds dr + C dr²:
// 6 mul, 2 add); per texel inside: its weight (a table indexed by r²) and sum.
constexpr Ops kOpsEwaTest{/*add*/ 4, /*mul*/ 6};
constexpr Ops kOpsEwaTexel{/*add*/ 4, /*mul*/ 3, 0, 0, 0, /*lut*/ 1, /*fetch*/ 1};

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

template <class T>
void Sampler::nearest(const core::Texture& t, int level, T u, T v, T out[3], Ops& ops) {
  T s, r;
  texel_coordinates(t, u, v, s, r);
  // Rounding to the nearest texel is wiring.
  const int x = wrap(int(std::floor(value(s) + 0.5f)), t.width, t.wrap);
  const int y = wrap(int(std::floor(value(r) + 0.5f)), t.height, t.wrap);
  touch(level, x, y);
  const glm::vec4& c = t.texels[size_t(y) * size_t(t.width) + size_t(x)];
  out[0] = T(c[0]), out[1] = T(c[1]), out[2] = T(c[2]);
  ops += kOpsNearest;
}

template <class T>
void Sampler::bilinear(const core::Texture& t, int level, T u, T v, T out[3], Ops& ops) {
  T s, r;
  texel_coordinates(t, u, v, s, r);
  const float fs = std::floor(value(s)), fr = std::floor(value(r));
  const T a = s - T(fs), b = r - T(fr);
  const int x0 = wrap(int(fs), t.width, t.wrap), x1 = wrap(int(fs) + 1, t.width, t.wrap);
  const int y0 = wrap(int(fr), t.height, t.wrap), y1 = wrap(int(fr) + 1, t.height, t.wrap);
  touch(level, x0, y0), touch(level, x1, y0), touch(level, x0, y1), touch(level, x1, y1);
  const glm::vec4* row0 = &t.texels[size_t(y0) * size_t(t.width)];
  const glm::vec4* row1 = &t.texels[size_t(y1) * size_t(t.width)];
  const glm::vec4 t00 = row0[x0], t10 = row0[x1], t01 = row1[x0], t11 = row1[x1];
  for (int c = 0; c < 3; ++c) {
    const T top = T(t00[c]) + (T(t10[c]) - T(t00[c])) * a;
    const T bottom = T(t01[c]) + (T(t11[c]) - T(t01[c])) * a;
    out[c] = top + (bottom - top) * b;
  }
  ops += kOpsBilinear;
}

template <class T>
void Sampler::trilinear(const MipMap& map, T lod, T u, T v, T out[3], Ops& ops) {
  const int last = int(map.levels.size()) - 1;
  const int l0 = std::min(int(value(lod)), last);
  bilinear(*map.levels[size_t(l0)], l0, u, v, out, ops);
  if (l0 == last || lod <= T(float(l0))) return;  // on a level: one probe
  const T f = lod - T(float(l0));
  T upper[3];
  bilinear(*map.levels[size_t(l0) + 1], l0 + 1, u, v, upper, ops);
  for (int c = 0; c < 3; ++c) out[c] += (upper[c] - out[c]) * f;
  ops += kOpsLevelBlend;
}

template <class T>
void Sampler::anisotropic(const MipMap& map, T u, T v, T du_major, T dv_major, T major2, T minor2, T out[3],
                          Ops& ops) {
  // Probes along the major axis, spaced by its length over N; the level of that
  // spacing, but never finer than the minor axis. As many probes as the footprint's
  // anisotropy asks, up to `probes`: N = ⌈major/minor⌉ (the ratio's root and quotient
  // computed always, as in hardware, and selected when the minor axis is not 0).
  const T root = sqrt_op(major2 / minor2);
  const T ratio = minor2 > T(0.0f) ? root : T(float(probes_));
  const T ratio_down = ratio - T(1e-3f);
  const int count = std::isfinite(value(ratio)) ? std::clamp(int(std::ceil(value(ratio_down))), 1, probes_) : probes_;
  const float n = float(count);
  const T lod = lod_of(std::max(minor2, major2 / (T(n) * T(n))), float(map.levels.size() - 1), ops);
  lod_ = value(lod);
  const T du = over_probes(du_major, n), dv = over_probes(dv_major, n);
  ops += Ops{/*add*/ 1, /*mul*/ 1, /*div*/ 2, /*sqrt*/ 1};  // the ratio, N², major²/N²
  ops.mul += 2;                                          // the step: 2 mul by 1/N (a table)
  T sum[3] = {T(0.0f), T(0.0f), T(0.0f)};
  for (int k = 0; k < count; ++k) {
    const float offset = float(k) + 0.5f - 0.5f * n;  // centred on the pixel (a table by k and N)
    T probe[3];
    trilinear(map, lod, u + du * offset, v + dv * offset, probe, ops);
    for (int c = 0; c < 3; ++c) sum[c] += probe[c];
    ops += Ops{/*add*/ 5, /*mul*/ 2};  // the probe's position, the sum
  }
  for (int c = 0; c < 3; ++c) out[c] = over_probes(sum[c], n);
  ops += Ops{0, /*mul*/ 3};  // by 1/N
}

template <class T>
void Sampler::ewa(const MipMap& map, T u, T v, T ax, T ay, T bx, T by, T out[3], Ops& ops) {
  // The ellipse inscribed in the pixel's footprint: the half-axes are half the uv
  // derivatives (the pixel spans ±½ around its centre), in texel coordinates of level 0
  // (s right, r down: r runs against v). Its matrix M = J·Jᵀ (J the half-axes as
  // columns): the points x with xᵀ M⁻¹ x < 1.
  const T half(0.5f), quarter(0.25f);
  ax = shifted(ax, half), bx = shifted(bx, half), ay = -shifted(ay, half), by = -shifted(by, half);
  T p = ax * ax + bx * bx, q = ax * ay + bx * by, r = ay * ay + by * by;
  // The true axes are M's eigenvalues: major² = λ1, minor² = λ2. At most 16 : 1, by
  // widening (M + c·I) — else a long ellipse would read a very fine level.
  const T p_r = p - r;
  const T mean = shifted(p + r, half), dev = sqrt_op(shifted(p_r * p_r, quarter) + q * q);
  const T major2 = mean + dev;
  T minor2 = mean - dev;
  constexpr float kMaxEccentricity2 = 16 * 16;  // (a power of two: multiplying by it is wiring)
  if (value(minor2) * kMaxEccentricity2 < value(major2)) {
    const T widen = T(value(major2) / kMaxEccentricity2) - minor2;
    p += widen, r += widen, minor2 += widen;
  } else {
    count_discarded<T>(Ops{/*add*/ 4});  // the widening computed, not selected
  }
  const int last = int(map.levels.size()) - 1;
  const int level = int(value(lod_of(minor2, float(last), ops)));
  lod_ = float(level);
  const core::Texture& t = *map.levels[size_t(level)];
  const core::Texture& base = *map.levels.front();
  // To the level's texels, axis by axis (a non-square texture's short side stops at 1;
  // the factors are the level's constants).
  const float ks = float(t.width) / float(base.width), kr = float(t.height) / float(base.height);
  p *= ks * ks, q *= ks * kr, r *= kr * kr;
  // Widened by a unit reconstruction filter (Heckbert's +1), then the quadratic form of
  // M⁻¹: A s² + B s r + C r² < 1 (−2q: a shift and a sign, wiring).
  p += 1.0f, r += 1.0f;
  const T det = p * r - q * q;
  const T A = r / det, B = T(-2 * value(q)) / det, C = p / det;
  // The ellipse's bounding box, no larger than the level (at the coarsest level a huge
  // footprint covers the whole texture, and every texel once is enough).
  const T half_s = std::min(sqrt_op(p), T(float(t.width))), half_r = std::min(sqrt_op(r), T(float(t.height)));
  T s0, r0;
  texel_coordinates(t, u, v, s0, r0);
  const int x_lo = int(std::ceil(value(s0 - half_s))), x_hi = int(std::floor(value(s0 + half_s)));
  const int y_lo = int(std::ceil(value(r0 - half_r))), y_hi = int(std::floor(value(r0 + half_r)));
  ops += kOpsEwaSetup;
  T sum[3] = {T(0.0f), T(0.0f), T(0.0f)}, weights = T(0.0f);
  for (int y = y_lo; y <= y_hi; ++y)
    for (int x = x_lo; x <= x_hi; ++x) {
      const T ds = T(float(x)) - s0, dr = T(float(y)) - r0;
      const T r2 = A * ds * ds + B * ds * dr + C * dr * dr;
      ops += kOpsEwaTest;
      if (r2 >= 1.0f) continue;
      // A Gaussian of the elliptical radius: one table look-up, indexed by r².
      const T w = exp_op(T(-2.0f * value(r2)));
      int tx = x % t.width, ty = y % t.height;
      if (t.wrap == core::Wrap::Repeat) tx += tx < 0 ? t.width : 0, ty += ty < 0 ? t.height : 0;
      else tx = std::clamp(x, 0, t.width - 1), ty = std::clamp(y, 0, t.height - 1);
      touch(level, tx, ty);
      const glm::vec4& c = t.texels[size_t(ty) * size_t(t.width) + size_t(tx)];
      for (int k = 0; k < 3; ++k) sum[k] += w * T(c[k]);
      weights += w;
      ops += kOpsEwaTexel;
    }
  if (weights > 0.0f) {
    for (int k = 0; k < 3; ++k) out[k] = sum[k] / weights;
    ops += Ops{0, 0, /*div*/ 3};
  } else {  // no texel centre inside (cannot happen with the +1): bilinear
    bilinear(t, level, u, v, out, ops);
  }
}

template <class T>
void Sampler::sample_as(const MipMap& map, T u, T v, T dudx, T dvdx, T dudy, T dvdy, T out[3], Ops& ops) {
  lines_.clear();
  map_ = &map;
  const uint64_t fetches_before = ops.fetch;
  const core::Texture& base = *map.levels.front();
  const float W = float(base.width), H = float(base.height);
  const float last = float(map.levels.size() - 1);
  // The footprint's axes in texels of the finest level (4 mul).
  const T ax = dudx * W, ay = dvdx * H, bx = dudy * W, by = dvdy * H;
  ops.mul += 4;
  if (filter_ == Filter::Ewa) {
    ewa(map, u, v, ax, ay, bx, by, out, ops);
  } else {
    // Their squared lengths (4 mul, 2 add).
    const T a2 = ax * ax + ay * ay, b2 = bx * bx + by * by;
    ops += Ops{/*add*/ 2, /*mul*/ 4};
    if (filter_ == Filter::Anisotropic) {
      const bool a_major = a2 >= b2;
      anisotropic(map, u, v, a_major ? dudx : dudy, a_major ? dvdx : dvdy, a_major ? a2 : b2, a_major ? b2 : a2, out,
                  ops);
    } else {
      const T lod = lod_of(std::max(a2, b2), last, ops);
      lod_ = value(lod);
      if (filter_ == Filter::Trilinear) {
        trilinear(map, lod, u, v, out, ops);
      } else {
        const int level = std::min(int(lod_ + 0.5f), int(last));  // the nearest level
        if (filter_ == Filter::Bilinear) bilinear(*map.levels[size_t(level)], level, u, v, out, ops);
        else nearest(*map.levels[size_t(level)], level, u, v, out, ops);
      }
    }
  }
  ops.line += uint64_t(lines_.size());
  if (memory_) read_lines();
  cycles_ += std::max<uint64_t>(1, (ops.fetch - fetches_before + 3) / 4);
}

template void Sampler::sample_as(const MipMap&, float, float, float, float, float, float, float[3], Ops&);
template void Sampler::sample_as(const MipMap&, Counted<float>, Counted<float>, Counted<float>, Counted<float>,
                                 Counted<float>, Counted<float>, Counted<float>[3], Ops&);

}  // namespace shadetlm::modules

namespace shadetlm::modules {

template <class T>
void sample_span(const TriangleSetup& t, const SpanPacket& p, const MipMap& map, Sampler& sampler,
                 float out[3][kSpanMax], Ops& ops, ValueRange& uv_range, uint16_t cycles[kSpanMax],
                 float (*uv_lod)[kSpanMax], uint16_t* lines) {
  if (p.count == 0) return;  // an empty span: no seeds computed, none counted
  const int dx = p.x0 - t.x_ref, dy = p.y - t.y_ref;
  const Plane &pu = t.uv[0], &pv = t.uv[1], &pw = t.inv_w;
  // The planes' seeds at the span's first pixel, as Plane::at computes them.
  T u_w = T(pu.a0) + T(pu.ax) * float(dx) + T(pu.ay) * float(dy);
  T v_w = T(pv.a0) + T(pv.ax) * float(dx) + T(pv.ay) * float(dy);
  uv_range.add_span(value(u_w), pu.ax, p.count, p.w);
  uv_range.add_span(value(v_w), pv.ax, p.count, p.w);
  for (int i = 0; i < p.count; ++i) {
    const T w = T(p.w[i]);
    const T u = u_w * w, v = v_w * w;
    const T dudx = (T(pu.ax) - u * pw.ax) * w, dvdx = (T(pv.ax) - v * pw.ax) * w;
    const T dudy = (T(pu.ay) - u * pw.ay) * w, dvdy = (T(pv.ay) - v * pw.ay) * w;
    u_w += pu.ax, v_w += pv.ax;
    T value_out[3];
    const uint64_t before = sampler.cycles();
    sampler.sample_as(map, u, v, dudx, dvdx, dudy, dvdy, value_out, ops);
    cycles[i] = uint16_t(std::min<uint64_t>(sampler.cycles() - before, 65535));
    if (lines) lines[i] = sampler.memory()->take_pixel_lines();
    for (int c = 0; c < 3; ++c) out[c][i] = value(value_out[c]);
    if (uv_lod) uv_lod[0][i] = value(u), uv_lod[1][i] = value(v), uv_lod[2][i] = sampler.last_lod();
  }
  ops += kOpsSpanUvPerPixel * uint64_t(p.count) + kOpsSpanUvPerSpan;
}

template void sample_span<float>(const TriangleSetup&, const SpanPacket&, const MipMap&, Sampler&,
                                 float[3][kSpanMax], Ops&, ValueRange&, uint16_t[kSpanMax], float (*)[kSpanMax],
                                 uint16_t*);
template void sample_span<Counted<float>>(const TriangleSetup&, const SpanPacket&, const MipMap&, Sampler&,
                                          float[3][kSpanMax], Ops&, ValueRange&, uint16_t[kSpanMax],
                                          float (*)[kSpanMax], uint16_t*);

}  // namespace shadetlm::modules
