#include "shadetlm/modules/lighting/lighting_kernel.hpp"

#include <cmath>
#include <type_traits>

#include "shadetlm/numeric/vector.hpp"
#include "shadetlm/modules/lighting/power.hpp"

namespace shadetlm::modules {

LightingKernel::LightingKernel(const core::Scene& scene, core::NumberFormat format)
    : numbers_(format), checks_(checks_outputs(format, false)) {
  for (int c = 0; c < 3; ++c) ambient_[c] = float(scene.ambient[c]);
  const glm::dvec3 view = -scene.camera.forward();
  for (const auto& l : scene.lights) {
    Light s;
    const glm::dvec3 rad = l.radiance();
    const glm::dvec3 dir = -l.direction;
    const glm::dvec3 h = glm::normalize(dir + view);  // only used when constant
    for (int c = 0; c < 3; ++c) s.radiance[c] = float(rad[c]), s.l[c] = float(dir[c]), s.h[c] = float(h[c]);
    s.l_varies = l.type == core::Light::Type::Point;
    s.h_varies = s.l_varies || scene.camera.local_viewer;
    lights_.push_back(s);
  }
}

Ops LightingKernel::ops_per_pixel(bool textured) const {
  // Per light: N·L and N·H (6 mul, 4 add), the power (1 lut), the diffuse and specular
  // terms (6 mul) and their sum into C (6 add); a texture multiplies the diffuse
  // colour (3 mul per light) and the ambient term (3 mul).
  Ops per_light{/*add*/ 10, /*mul*/ 12, 0, 0, 0, /*lut*/ 1};
  if (textured) per_light.mul += 3;
  Ops o = per_light * lights_.size();
  if (textured) o.mul += 3;
  return o;
}

Ops LightingKernel::ops_per_span() const {
  // The material's colours times each light's radiance, and the ambient colour.
  return Ops{0, /*mul*/ 3 + 6 * uint64_t(lights_.size())};
}

void LightingKernel::process(SpanPacket& p) {
  const core::Material& m = *p.tri->material;
  const bool deferred = m.path == core::ShadingPath::TextureObject;
  const bool textured = m.texture >= 0 && !deferred;
  with_number_type(numbers_, [&](auto zero) { shade<decltype(zero)>(p); });
  if (checks_) nonfinite_ += count_nonfinite(p.rgb, p.count) + (deferred ? count_nonfinite(p.spec, p.count) : 0);
  tally_.add(textured ? 1 : 0, p.count);
}

Ops LightingKernel::ops() const {
  Ops o;
  for (int textured = 0; textured < 2; ++textured)
    o += ops_per_pixel(textured) * tally_.pixels[textured] + ops_per_span() * tally_.packets[textured];
  return o;
}

template <class T>
void LightingKernel::shade(SpanPacket& p) {
  const core::Material& m = *p.tri->material;
  // texture-object: the texture is splatted after the frame (texel_project), so the
  // ambient and diffuse factor D goes to rgb and the specular term S apart.
  const bool deferred = m.path == core::ShadingPath::TextureObject;
  const bool textured = m.texture >= 0 && !deferred;
  const float shininess = float(m.shininess);  // the power table's content
  T ambient[3], kd[kMaxLights][3], ks[kMaxLights][3];
  for (int c = 0; c < 3; ++c) ambient[c] = T(ambient_[c]) * T(float(m.ambient[c]));
  for (size_t k = 0; k < lights_.size(); ++k)
    for (int c = 0; c < 3; ++c) {
      kd[k][c] = T(lights_[k].radiance[c]) * T(float(m.diffuse[c]));
      ks[k][c] = T(lights_[k].radiance[c]) * T(float(m.specular[c]));
    }
  // Lights outer, pixels inner: straight pixel loops over arrays, which the compiler
  // vectorizes in float32; each pixel's arithmetic is the formula above, in order.
  // float32 in whole groups of lanes (kLanes: no scalar tails), the other formats pixel by pixel.
  const int count = std::is_same_v<T, float> ? lanes(p.count) : p.count;
  const T zero = T(0.0f);
  // The sums: the packet's arrays in float32, registers of the format else.
  T rgb_regs[3][kSpanMax], spec_regs[3][kSpanMax];
  T(*rgb)[kSpanMax] = rgb_regs;
  T(*spec)[kSpanMax] = spec_regs;
  if constexpr (std::is_same_v<T, float>) rgb = p.rgb, spec = p.spec;
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < count; ++i) rgb[c][i] = textured ? ambient[c] * T(p.tex[c][i]) : ambient[c];
  if (deferred)
    for (int c = 0; c < 3; ++c)
      for (int i = 0; i < count; ++i) spec[c][i] = zero;
  T n_dot_l[kSpanMax], n_dot_h[kSpanMax];
  if (capture_ && lights_.empty())  // no light: nothing to show, not a stale value
    for (int i = 0; i < count; ++i) captured_[0][i] = captured_[1][i] = 0;
  // Fetched-normal bump paths light in the texture's space: L and H come per pixel.
  const bool in_space = core::fetches_normal(m.path);
  for (size_t k = 0; k < lights_.size(); ++k) {
    const Light& s = lights_[k];
    const T l_const[3] = {T(s.l[0]), T(s.l[1]), T(s.l[2])}, h_const[3] = {T(s.h[0]), T(s.h[1]), T(s.h[2])};
    // N·L and N·H, with L and H from the packet or constant: one straight loop per case,
    // so that each vectorizes.
    auto dots = [&](auto l_varies, auto h_varies) {
      for (int i = 0; i < count; ++i) {
        const T n[3] = {T(p.n[0][i]), T(p.n[1][i]), T(p.n[2][i])};
        const T l[3] = {l_varies ? T(p.l[k][0][i]) : l_const[0], l_varies ? T(p.l[k][1][i]) : l_const[1],
                        l_varies ? T(p.l[k][2][i]) : l_const[2]};
        const T h[3] = {h_varies ? T(p.h[k][0][i]) : h_const[0], h_varies ? T(p.h[k][1][i]) : h_const[1],
                        h_varies ? T(p.h[k][2][i]) : h_const[2]};
        n_dot_l[i] = dot3(n, l);
        n_dot_h[i] = dot3(n, h);
      }
    };
    using yes = std::true_type;
    using no = std::false_type;
    if (in_space || (s.l_varies && s.h_varies)) dots(yes{}, yes{});
    else if (s.h_varies) dots(no{}, yes{});
    else if (s.l_varies) dots(yes{}, no{});
    else dots(no{}, no{});
    if (capture_ && k == 0)
      for (int i = 0; i < count; ++i) captured_[0][i] = float(n_dot_l[i]), captured_[1][i] = float(n_dot_h[i]);
    // No highlight from a light behind the surface (and none where H is undefined).
    // Hardware looks the power up for every pixel (counted so). In float32 so does the
    // model, then selects; the other formats skip the power the select would discard.
    if constexpr (std::is_same_v<T, float>) {  // branch-free: the loop vectorizes
      for (int i = 0; i < count; ++i) {
        const bool lit = (n_dot_l[i] > zero) & (n_dot_h[i] > zero);
        const float power = specular_power(lit ? n_dot_h[i] : 1.0f, shininess);
        n_dot_h[i] = lit ? power : zero;
      }
    } else {
      for (int i = 0; i < count; ++i) {
        const bool lit = n_dot_l[i] > zero && n_dot_h[i] > zero;
        if (!lit) count_discarded<T>(Ops{0, 0, 0, 0, 0, /*lut*/ 1});  // looked up, then discarded
        n_dot_h[i] = lit ? pow_op(n_dot_h[i], shininess) : zero;
      }
    }
    if (deferred) {
      for (int c = 0; c < 3; ++c)
        for (int i = 0; i < count; ++i) {
          rgb[c][i] += kd[k][c] * (n_dot_l[i] > zero ? n_dot_l[i] : zero);
          spec[c][i] += ks[k][c] * n_dot_h[i];
        }
      continue;
    }
    for (int c = 0; c < 3; ++c)
      for (int i = 0; i < count; ++i) {
        const T diffuse = n_dot_l[i] > zero ? n_dot_l[i] : zero;
        const T d = textured ? kd[k][c] * T(p.tex[c][i]) : kd[k][c];
        rgb[c][i] += d * diffuse + ks[k][c] * n_dot_h[i];
      }
  }
  if constexpr (!std::is_same_v<T, float>) {
    for (int c = 0; c < 3; ++c)
      for (int i = 0; i < count; ++i) p.rgb[c][i] = float(rgb[c][i]);
    if (deferred)
      for (int c = 0; c < 3; ++c)
        for (int i = 0; i < count; ++i) p.spec[c][i] = float(spec[c][i]);
  }
}

}  // namespace shadetlm::modules
