#include "modules/texture_fetch/texture_fetch_kernel.hpp"

#include <cmath>

namespace modules {

bool TextureFetchKernel::needed(const core::Scene& scene) {
  for (const auto& o : scene.objects)
    if (scene.materials[o.material].texture >= 0) return true;
  return false;
}

void TextureFetchKernel::process(SpanPacket& p) {
  const TriangleSetup& t = *p.tri;
  const core::Texture& tex = scene_.textures[t.material->texture];
  const int dx = p.x0 - t.x_ref, dy = p.y - t.y_ref;
  float u_w = t.uv[0].at(dx, dy), v_w = t.uv[1].at(dx, dy);
  const float W = float(tex.width), H = float(tex.height);
  for (int i = 0; i < p.count; ++i) {
    const float u = u_w * p.w[i], v = v_w * p.w[i];
    u_w += t.uv[0].ax;
    v_w += t.uv[1].ax;
    float s = u * W - 0.5f, r = (1.0f - v) * H - 0.5f;
    // Far coordinates are brought near first (as in core::Texture::bilinear).
    if (tex.wrap == core::Wrap::Repeat) {
      s -= W * std::floor(s / W);
      r -= H * std::floor(r / H);
    } else {
      s = std::fmin(std::fmax(s, -1.0f), W);
      r = std::fmin(std::fmax(r, -1.0f), H);
    }
    const float fs = std::floor(s), fr = std::floor(r);
    const float a = s - fs, b = r - fr;
    const int x = int(fs), y = int(fr);
    const glm::dvec4 t00 = tex.texel(x, y), t10 = tex.texel(x + 1, y);
    const glm::dvec4 t01 = tex.texel(x, y + 1), t11 = tex.texel(x + 1, y + 1);
    for (int c = 0; c < 3; ++c) {
      const float top = float(t00[c]) + (float(t10[c]) - float(t00[c])) * a;
      const float bottom = float(t01[c]) + (float(t11[c]) - float(t01[c])) * a;
      p.tex[c][i] = top + (bottom - top) * b;
    }
  }
  ops_ += kOpsPerPixel * uint64_t(p.count);
  if (p.count > 0) ops_ += kOpsPerSpan;
}

}  // namespace modules
