#include "modules/lighting/lighting_kernel.hpp"

#include <cmath>

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
  const bool textured = m.texture >= 0;
  const float shininess = float(m.shininess);
  float ambient[3], kd[kMaxLights][3], ks[kMaxLights][3];
  for (int c = 0; c < 3; ++c) ambient[c] = ambient_[c] * float(m.ambient[c]);
  for (size_t k = 0; k < lights_.size(); ++k)
    for (int c = 0; c < 3; ++c) {
      kd[k][c] = lights_[k].radiance[c] * float(m.diffuse[c]);
      ks[k][c] = lights_[k].radiance[c] * float(m.specular[c]);
    }
  for (int i = 0; i < p.count; ++i) {
    const float n[3] = {p.n[0][i], p.n[1][i], p.n[2][i]};
    float tex[3] = {1, 1, 1};
    float rgb[3] = {ambient[0], ambient[1], ambient[2]};
    if (textured)
      for (int c = 0; c < 3; ++c) tex[c] = p.tex[c][i], rgb[c] = rgb[c] * tex[c];
    for (size_t k = 0; k < lights_.size(); ++k) {
      const Light& s = lights_[k];
      float l[3], h[3];
      for (int c = 0; c < 3; ++c) {
        l[c] = s.l_varies ? p.l[k][c][i] : s.l[c];
        h[c] = s.h_varies ? p.h[k][c][i] : s.h[c];
      }
      const float n_dot_l = dot3(n, l), n_dot_h = dot3(n, h);
      const float diffuse = n_dot_l > 0 ? n_dot_l : 0.0f;
      const float power = std::pow(n_dot_h > 0 ? n_dot_h : 0.0f, shininess);
      // No highlight from a light behind the surface (and none where H is undefined).
      const float specular = n_dot_l > 0 && n_dot_h > 0 ? power : 0.0f;
      for (int c = 0; c < 3; ++c) {
        const float d = textured ? kd[k][c] * tex[c] : kd[k][c];
        rgb[c] += d * diffuse + ks[k][c] * specular;
      }
    }
    for (int c = 0; c < 3; ++c) p.rgb[c][i] = rgb[c];
  }
  ops_ += ops_per_pixel(textured) * uint64_t(p.count);
  if (p.count > 0) ops_ += ops_per_span();
}

}  // namespace modules
