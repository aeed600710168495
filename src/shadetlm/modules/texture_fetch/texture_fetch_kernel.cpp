#include "shadetlm/modules/texture_fetch/texture_fetch_kernel.hpp"

#include <algorithm>
#include <cmath>

#include "shadetlm/core/bump_map.hpp"

namespace shadetlm::modules {

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
  if (options.cache) {  // every texture's levels one after another in the unit's memory
    memory_ = std::make_unique<MemoryClient>(*options.cache);
    for (size_t k = 0; k < scene.textures.size(); ++k) {
      if (maps_[k].levels.empty()) {
        base_surfaces_.push_back(memory_->place(scene.textures[k].width, scene.textures[k].height, 4));
      } else {
        place(maps_[k], *memory_);
        base_surfaces_.push_back(maps_[k].surfaces.front());
      }
    }
    sampler_.set_memory(memory_.get());
  }
}

// Phong's bilinear read through the cache: the footprint's lines, each once.
void TextureFetchKernel::read_footprint(const Surface& s, int x0, int y0, int x1, int y1, int i) {
  footprint_.clear();
  for (const auto& [x, y] : {std::pair{x0, y0}, {x1, y0}, {x0, y1}, {x1, y1}}) footprint_.add(memory_->line_of(s, x, y));
  footprint_.for_each([&](uint64_t line) { memory_->read_line(line); });
  lines_[i] = memory_->take_pixel_lines();
}

void TextureFetchKernel::process_filtered(SpanPacket& p) {
  sample_span(*p.tri, p, maps_[size_t(p.tri->material->texture)], sampler_, p.tex, ops_, uv_range_, work_,
              capture_ ? captured_ : nullptr, memory_ ? lines_ : nullptr);
  lod_computations_ += uint64_t(p.count);
  if (capture_)  // u, v, LOD from sample_span; no single texel address
    for (int i = 0; i < p.count; ++i) captured_[4][i] = captured_[2][i], captured_[2][i] = captured_[3][i] = -1;
}

void TextureFetchKernel::fetch(SpanPacket& p) {
  if (p.tri->material->path == core::ShadingPath::TextureScreen) return process_filtered(p);
  std::fill(work_, work_ + p.count, uint16_t(1));
  const TriangleSetup& t = *p.tri;
  const core::Texture& tex = scene_.textures[t.material->texture];
  const int dx = p.x0 - t.x_ref, dy = p.y - t.y_ref;
  float u_w = t.uv[0].at(dx, dy), v_w = t.uv[1].at(dx, dy);
  const float W = float(tex.width), H = float(tex.height);
  const bool parallax = t.material->path == core::ShadingPath::Parallax;  // uv from the parallax block
  for (int i = 0; i < p.count; ++i) {
    const float u = parallax ? p.uvp[0][i] : u_w * p.w[i], v = parallax ? p.uvp[1][i] : v_w * p.w[i];
    u_w += t.uv[0].ax;
    v_w += t.uv[1].ax;
    // The same addressing as the texture unit's Sampler (sampling/sampler.cpp),
    // written out here on purpose: through the Sampler this read cost 7 % more
    // instructions on the benchmark scene (callgrind), on the most common textured path.
    float s = u * W - 0.5f, r = (1.0f - v) * H - 0.5f;
    // Far coordinates are brought near first (as in core::Texture::bilinear).
    if (tex.wrap == core::Wrap::Repeat) {
      s -= W * std::floor(s / W);
      r -= H * std::floor(r / H);
      // A tiny negative s rounds to exactly W above: bring it back into [0, W).
      if (s >= W) s -= W;
      if (r >= H) r -= H;
    } else {
      s = std::fmin(std::fmax(s, -1.0f), W);
      r = std::fmin(std::fmax(r, -1.0f), H);
    }
    const float fs = std::floor(s), fr = std::floor(r);
    const float a = s - fs, b = r - fr;
    // The texel addresses of core::Texture::texel: s, r are now within one texel of
    // the texture, so the wrap is a compare (repeat) or a clamp.
    int x0 = int(fs), y0 = int(fr), x1 = x0 + 1, y1 = y0 + 1;
    if (tex.wrap == core::Wrap::Repeat) {
      x0 = x0 >= tex.width ? x0 - tex.width : x0, y0 = y0 >= tex.height ? y0 - tex.height : y0;
      x1 = x1 >= tex.width ? x1 - tex.width : x1, y1 = y1 >= tex.height ? y1 - tex.height : y1;
    } else {
      x0 = std::clamp(x0, 0, tex.width - 1), x1 = std::clamp(x1, 0, tex.width - 1);
      y0 = std::clamp(y0, 0, tex.height - 1), y1 = std::clamp(y1, 0, tex.height - 1);
    }
    if (capture_)
      captured_[0][i] = u, captured_[1][i] = v, captured_[2][i] = float(x0), captured_[3][i] = float(y0), captured_[4][i] = 0;
    if (memory_) read_footprint(base_surfaces_[size_t(t.material->texture)], x0, y0, x1, y1, i);
    const glm::vec4* row0 = &tex.texels[size_t(y0) * tex.width];
    const glm::vec4* row1 = &tex.texels[size_t(y1) * tex.width];
    const glm::vec4 t00 = row0[x0], t10 = row0[x1], t01 = row1[x0], t11 = row1[x1];
    for (int c = 0; c < 3; ++c) {
      const float top = t00[c] + (t10[c] - t00[c]) * a;
      const float bottom = t01[c] + (t11[c] - t01[c]) * a;
      p.tex[c][i] = top + (bottom - top) * b;
    }
  }
  ops_ += kOpsPerPixel * uint64_t(p.count);
  if (p.count > 0) ops_ += kOpsPerSpan;
}

}  // namespace shadetlm::modules
