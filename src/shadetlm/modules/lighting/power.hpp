#pragma once
// The specular power x^e of the float32 datapath, for 0 < x (N·H, at most 1 but for
// rounding) and 0 ≤ e ≤ 10⁶ (the shininess), as
//
//   x^e = 2^(e · log2 x)
//
// in float arithmetic, branch-free and with no call, so that the compiler vectorizes the
// lighting block's loop over a packet (libm's powf is one call per pixel: 40 of the
// minimal Phong path's 256 instructions a pixel, docs/performance.md). Each step is a
// textbook series, checkable by hand:
//
//   x = m · 2^k, m in [√½, √2)          (the float's exponent and mantissa fields)
//   ln m = 2 atanh s = 2 (s + s³/3 + s⁵/5 + s⁷/7 + s⁹/9 + …),  s = (m − 1)/(m + 1), |s| ≤ 0.1716
//   y = e · (k + ln m / ln 2)
//   2^y = 2^n · exp(t),  n = y rounded to nearest, t = (y − n) ln 2, |t| ≤ 0.347,
//   exp t = 1 + t + t²/2! + … + t⁷/7!
//
// Truncation: the next terms are s¹¹/11 (2e-9 of ln m) and t⁸/8! (6e-9), under float's
// rounding. The result is within a few float ulps of the exact power plus an error
// relative to |y| (y's own rounding, amplified by exp): testbenches/test_lighting.cpp
// bounds both against double. Results under 2⁻¹²⁶ (y < −126) are returned as 0 and y is
// clamped at 127 (x > 1 only by rounding); the golden model computes the exact power.
#include <cstdint>
#include <cstring>

namespace shadetlm::modules {

// Every step is computed and the ternaries select values (no operation behind a
// condition): the compiler if-converts and vectorizes only that.
inline float specular_power(float x, float e) {
  // x = m · 2^k: a subnormal x is first scaled into the normal range.
  const bool subnormal = x < 0x1p-126f;
  const float xs = x * (subnormal ? 0x1p23f : 1.0f);
  uint32_t bits;
  std::memcpy(&bits, &xs, sizeof bits);
  int k = int(bits >> 23) - 127 - (subnormal ? 23 : 0);  // x > 0: the sign bit is clear
  bits = (bits & 0x007fffffu) | 0x3f800000u;              // m in [1, 2)
  float m;
  std::memcpy(&m, &bits, sizeof m);
  const bool above = m > 1.41421356f;  // fold m into [√½, √2): |s| stays small
  m *= above ? 0.5f : 1.0f;
  k += above ? 1 : 0;
  const float s = (m - 1.0f) / (m + 1.0f), s2 = s * s;
  const float ln_m = 2.0f * s * (1.0f + s2 * (1.0f / 3 + s2 * (1.0f / 5 + s2 * (1.0f / 7 + s2 * (1.0f / 9)))));
  float y = e * (float(k) + ln_m * 1.44269504f);  // 1/ln 2
  const bool underflow = y < -126.0f;
  y = underflow ? 0.0f : y < 127.0f ? y : 127.0f;
  // n = nearest integer of y: adding and removing 1.5 · 2²³ rounds (|y| ≤ 127), with no
  // call to nearbyint (a call without SSE4.1).
  const float n = (y + 0x1.8p23f) - 0x1.8p23f;
  const float t = (y - n) * 0.693147181f;  // ln 2
  const float exp_t =
      1.0f + t * (1.0f + t * (1.0f / 2 + t * (1.0f / 6 + t * (1.0f / 24 + t * (1.0f / 120 + t * (1.0f / 720 + t * (1.0f / 5040)))))));
  const uint32_t scale_bits = uint32_t(int(n) + 127) << 23;  // 2^n, n in [−126, 127]
  float scale;
  std::memcpy(&scale, &scale_bits, sizeof scale);
  return exp_t * (underflow ? 0.0f : scale);
}

}  // namespace shadetlm::modules
