#include "modules/texture_fetch/texture_fetch_kernel.hpp"

#include <algorithm>
#include <cmath>

#include "core/bump_map.hpp"

namespace modules {

bool TextureFetchKernel::needed(const core::Scene& scene) {
  for (const auto& o : scene.objects)
    if (scene.materials[o.material].texture >= 0 &&
        scene.materials[o.material].path != core::ShadingPath::TextureObject)
      return true;
  return false;
}

TextureFetchKernel::TextureFetchKernel(const core::Scene& scene, const Options& options)
    : scene_(scene), sampler_(options.filter, options.probes) {
  levels_.resize(scene.textures.size());
  maps_.resize(scene.textures.size());
  for (const auto& o : scene.objects) {
    const core::Material& m = scene.materials[size_t(o.material)];
    if (m.path != core::ShadingPath::TextureScreen || !maps_[size_t(m.texture)].levels.empty()) continue;
    const core::Texture& base = scene.textures[size_t(m.texture)];
    levels_[size_t(m.texture)] = core::mip_levels(base, false);
    MipMap& map = maps_[size_t(m.texture)];
    map.levels.push_back(&base);
    for (const auto& l : levels_[size_t(m.texture)]) map.levels.push_back(&l);
  }
}

void TextureFetchKernel::process_filtered(SpanPacket& p) {
  const uint64_t cycles_before = sampler_.cycles();
  sample_span(*p.tri, p, maps_[size_t(p.tri->material->texture)], sampler_, p.tex, ops_, uv_range_,
              capture_ ? captured_ : nullptr);
  last_cycles_ = sampler_.cycles() - cycles_before;
  lod_computations_ += uint64_t(p.count);
  if (capture_)  // u, v, LOD from sample_span; no single texel address
    for (int i = 0; i < p.count; ++i) captured_[4][i] = captured_[2][i], captured_[2][i] = captured_[3][i] = -1;
}

void TextureFetchKernel::process(SpanPacket& p) {
  if (p.tri->material->path == core::ShadingPath::TextureScreen) return process_filtered(p);
  last_cycles_ = 0;
  const TriangleSetup& t = *p.tri;
  const core::Texture& tex = scene_.textures[t.material->texture];
  const int dx = p.x0 - t.x_ref, dy = p.y - t.y_ref;
  float u_w = t.uv[0].at(dx, dy), v_w = t.uv[1].at(dx, dy);
  for (int i = 0; i < p.count; ++i) {
    const float u = u_w * p.w[i], v = v_w * p.w[i];
    u_w += t.uv[0].ax;
    v_w += t.uv[1].ax;
    // The texture unit's bilinear read, with the shared addressing convention.
    float texel[3];
    int first[2];
    sampler_.read_bilinear(tex, u, v, texel, ops_, first);
    for (int c = 0; c < 3; ++c) p.tex[c][i] = texel[c];
    if (capture_)
      captured_[0][i] = u, captured_[1][i] = v, captured_[2][i] = float(first[0]), captured_[3][i] = float(first[1]),
      captured_[4][i] = 0;
  }
  ops_ += kOpsUvPerPixel * uint64_t(p.count);
  if (p.count > 0) ops_ += kOpsPerSpan;
}

}  // namespace modules
