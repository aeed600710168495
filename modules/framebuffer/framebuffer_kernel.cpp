#include "modules/framebuffer/framebuffer_kernel.hpp"

#include <cmath>
#include <limits>

namespace modules {

FramebufferKernel::FramebufferKernel(const core::Scene& scene, bool deferred)
    : frame_(scene.camera.width, scene.camera.height) {
  if (deferred) {
    visible_.assign(frame_.pixel_count(), 0);
    specular_.assign(frame_.pixel_count() * 3, 0.0f);
  }
  const float background[3] = {float(scene.background.r), float(scene.background.g), float(scene.background.b)};
  const char* names[8] = {"R", "G", "B", "A", "Z", "N.X", "N.Y", "N.Z"};
  const float fill[8] = {background[0], background[1], background[2], 0.0f,
                         std::numeric_limits<float>::infinity(), 0.0f, 0.0f, 0.0f};
  for (int k = 0; k < 8; ++k) frame_.add(names[k], fill[k]);
  for (int k = 0; k < 8; ++k) layer_[k] = frame_.at(names[k]).data();
  // The parallax tracer's iterations per pixel, where a scene has a parallax material.
  for (const auto& o : scene.objects)
    if (scene.materials[size_t(o.material)].path == core::ShadingPath::Parallax)
      iterations_ = frame_.add("parallax.iterations").data();
  for (int k = 0; k < 8; ++k) layer_[k] = frame_.at(names[k]).data();  // adding may move the channels
}

void FramebufferKernel::process(SpanPacket& p) {
  const size_t base = size_t(p.y) * frame_.width + p.x0;
  for (int i = 0; i < p.count; ++i) {
    const size_t at = base + i;
    layer_[0][at] = p.rgb[0][i];
    layer_[1][at] = p.rgb[1][i];
    layer_[2][at] = p.rgb[2][i];
    layer_[3][at] = 1.0f;
    layer_[4][at] = p.w[i];
    layer_[5][at] = p.n[0][i];
    layer_[6][at] = p.n[1][i];
    layer_[7][at] = p.n[2][i];
  }
  if (iterations_) {  // 0 where a nearer surface without parallax covers the pixel
    const bool parallax = p.tri->material->path == core::ShadingPath::Parallax;
    for (int i = 0; i < p.count; ++i) iterations_[base + size_t(i)] = parallax ? p.iterations[i] : 0.0f;
  }
  // The last guard: a NaN or an infinity never reaches the frame. What arrives — colour,
  // specular term (composited later by texel_project), normal, depth — is counted (the
  // stress tests read the count; each block's own count says where it arose) and
  // written as 0 (depth: the largest float, as far as a covered pixel can be).
  const bool splatted = p.tri->material->path == core::ShadingPath::TextureObject;
  const uint64_t bad = count_nonfinite(p.w, p.count) + count_nonfinite(p.rgb, p.count) +
                       count_nonfinite(p.n, p.count) + (splatted ? count_nonfinite(p.spec, p.count) : 0);
  if (bad > 0) {
    nonfinite_ += bad;
    for (int l : {0, 1, 2, 5, 6, 7})
      for (int i = 0; i < p.count; ++i)
        if (!std::isfinite(layer_[l][base + i])) layer_[l][base + i] = 0.0f;
    for (int i = 0; i < p.count; ++i)
      if (!std::isfinite(layer_[4][base + i])) layer_[4][base + i] = std::numeric_limits<float>::max();
    if (splatted)
      for (int c = 0; c < 3; ++c)
        for (int i = 0; i < p.count; ++i)
          if (!std::isfinite(p.spec[c][i])) p.spec[c][i] = 0.0f;
  }
  if (visible_.empty()) return;
  for (int i = 0; i < p.count; ++i) {
    const size_t at = base + i;
    visible_[at] = splatted ? p.tri->source + 1 : 0;  // a nearer surface hides it
    if (splatted)
      for (int c = 0; c < 3; ++c) specular_[at * 3 + c] = p.spec[c][i];
  }
}

}  // namespace modules
