#include "modules/lighting/lighting_kernel.hpp"

#include <cmath>
#include <type_traits>

#include "modules/common/vector.hpp"

namespace modules {

LightingKernel::LightingKernel(const core::Scene& scene) {
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
  // texture-object: the texture is splatted after the frame (texel_project), so the
  // ambient and diffuse factor D goes to rgb and the specular term S apart.
  const bool deferred = m.path == core::ShadingPath::TextureObject;
  const bool textured = m.texture >= 0 && !deferred;
  const float shininess = float(m.shininess);
  float ambient[3], kd[kMaxLights][3], ks[kMaxLights][3];
  for (int c = 0; c < 3; ++c) ambient[c] = ambient_[c] * float(m.ambient[c]);
  for (size_t k = 0; k < lights_.size(); ++k)
    for (int c = 0; c < 3; ++c) {
      kd[k][c] = lights_[k].radiance[c] * float(m.diffuse[c]);
      ks[k][c] = lights_[k].radiance[c] * float(m.specular[c]);
    }
  // Lights outer, pixels inner: straight pixel loops over the packet's arrays, which
  // the compiler vectorizes; each pixel's arithmetic is the formula above, in order.
  const int count = p.count;
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < count; ++i) p.rgb[c][i] = textured ? ambient[c] * p.tex[c][i] : ambient[c];
  if (deferred)
    for (int c = 0; c < 3; ++c)
      for (int i = 0; i < count; ++i) p.spec[c][i] = 0;
  float n_dot_l[kSpanMax], n_dot_h[kSpanMax];
  if (capture_ && lights_.empty())  // no light: nothing to show, not a stale value
    for (int i = 0; i < count; ++i) captured_[0][i] = captured_[1][i] = 0;
  // Fetched-normal bump paths light in the texture's space: L and H come per pixel.
  const bool in_space = core::fetches_normal(m.path);
  for (size_t k = 0; k < lights_.size(); ++k) {
    const Light& s = lights_[k];
    // N·L and N·H, with L and H from the packet or constant: one straight loop per case,
    // so that each vectorizes.
    auto dots = [&](auto l_varies, auto h_varies) {
      for (int i = 0; i < count; ++i) {
        const float n[3] = {p.n[0][i], p.n[1][i], p.n[2][i]};
        const float l[3] = {l_varies ? p.l[k][0][i] : s.l[0], l_varies ? p.l[k][1][i] : s.l[1],
                            l_varies ? p.l[k][2][i] : s.l[2]};
        const float h[3] = {h_varies ? p.h[k][0][i] : s.h[0], h_varies ? p.h[k][1][i] : s.h[1],
                            h_varies ? p.h[k][2][i] : s.h[2]};
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
      for (int i = 0; i < count; ++i) captured_[0][i] = n_dot_l[i], captured_[1][i] = n_dot_h[i];
    // No highlight from a light behind the surface (and none where H is undefined).
    // Hardware looks the power up for every pixel (counted so); the model skips the
    // call whose result the select would discard.
    for (int i = 0; i < count; ++i)
      n_dot_h[i] = n_dot_l[i] > 0 && n_dot_h[i] > 0 ? std::pow(n_dot_h[i], shininess) : 0.0f;
    if (deferred) {
      for (int c = 0; c < 3; ++c)
        for (int i = 0; i < count; ++i) {
          p.rgb[c][i] += kd[k][c] * (n_dot_l[i] > 0 ? n_dot_l[i] : 0.0f);
          p.spec[c][i] += ks[k][c] * n_dot_h[i];
        }
      continue;
    }
    for (int c = 0; c < 3; ++c)
      for (int i = 0; i < count; ++i) {
        const float diffuse = n_dot_l[i] > 0 ? n_dot_l[i] : 0.0f;
        const float d = textured ? kd[k][c] * p.tex[c][i] : kd[k][c];
        p.rgb[c][i] += d * diffuse + ks[k][c] * n_dot_h[i];
      }
  }
  ops_ += ops_per_pixel(textured) * uint64_t(p.count);
  if (p.count > 0) ops_ += ops_per_span();
}

}  // namespace modules
