#include "shadetlm/modules/framebuffer/framebuffer_kernel.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace shadetlm::modules {

FramebufferKernel::FramebufferKernel(const core::Scene& scene, bool deferred, std::optional<CacheConfig> cache)
    : frame_(scene.camera.width, scene.camera.height) {
  if (cache) {
    memory_ = std::make_unique<MemoryClient>(*cache);
    colour_ = memory_->place(scene.camera.width, scene.camera.height, kColourBytes);
  }
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
  // The parallax tracer's iterations and hit per pixel, where a scene has a parallax
  // material; the golden model writes the exact hit in the same layers.
  bool parallax = false;
  for (const auto& o : scene.objects)
    parallax = parallax || scene.materials[size_t(o.material)].path == core::ShadingPath::Parallax;
  if (parallax) {
    for (const char* name : {"parallax.iterations", "parallax.u", "parallax.v", "parallax.height"}) frame_.add(name);
    iterations_ = frame_.at("parallax.iterations").data();
    hit_[0] = frame_.at("parallax.u").data(), hit_[1] = frame_.at("parallax.v").data();
    hit_[2] = frame_.at("parallax.height").data();
  }
  for (int k = 0; k < 8; ++k) layer_[k] = frame_.at(names[k]).data();  // adding may move the channels
}

namespace {

// dst[0 … n) = src[0 … n), returning how many of the values are NaN or infinite: one
// straight loop per layer, which the compiler vectorizes (eight layers in one loop it
// did not: 2 more instructions a pixel on golden/sphere).
uint32_t copy_counting_nonfinite(float* __restrict dst, const float* __restrict src, int n) {
  uint32_t bad = 0;
  for (int i = 0; i < n; ++i) {
    bad += is_nonfinite(src[i]);
    dst[i] = src[i];
  }
  return bad;
}

// dst[0 … n) = src[0 … n), a NaN or an infinity written as 0: branch-free, vectorized.
void copy_finite_or_zero(float* __restrict dst, const float* __restrict src, int n) {
  for (int i = 0; i < n; ++i) dst[i] = is_nonfinite(src[i]) ? 0.0f : src[i];
}

}  // namespace

void FramebufferKernel::write_colour(const SpanPacket& p) {
  for (int i = 0; i < p.count; ++i) {
    memory_->access(colour_, p.x0 + i, p.y, true);
    lines_[i] = memory_->take_pixel_lines();
  }
}

void FramebufferKernel::process(SpanPacket& p) {
  const size_t base = size_t(p.y) * frame_.width + p.x0;
  const int n = p.count;
  // The last guard: a NaN or an infinity never reaches the frame. What arrives — colour,
  // specular term (composited later by texel_project), normal, depth — is counted (the
  // stress tests read the count; each block's own count says where it arose) and
  // written as 0 (depth: the largest float, as far as a covered pixel can be).
  uint64_t bad = 0;
  for (int c = 0; c < 3; ++c) bad += copy_counting_nonfinite(layer_[c] + base, p.rgb[c], n);
  std::fill_n(layer_[3] + base, n, 1.0f);
  bad += copy_counting_nonfinite(layer_[4] + base, p.w, n);
  for (int c = 0; c < 3; ++c) bad += copy_counting_nonfinite(layer_[5 + c] + base, p.n[c], n);
  if (iterations_) {  // 0 where a nearer surface without parallax covers the pixel
    if (p.tri->material->path == core::ShadingPath::Parallax) {
      std::copy_n(p.iterations, n, iterations_ + base);
      const float* hit[3] = {p.uvp[0], p.uvp[1], p.hit_height};
      for (int k = 0; k < 3; ++k) copy_finite_or_zero(hit_[k] + base, hit[k], n);  // counted upstream
    } else {
      std::fill_n(iterations_ + base, n, 0.0f);
      for (int k = 0; k < 3; ++k) std::fill_n(hit_[k] + base, n, 0.0f);
    }
  }
  const bool splatted = p.tri->material->path == core::ShadingPath::TextureObject;
  if (splatted) bad += count_nonfinite(p.spec, n);
  if (bad > 0) {
    nonfinite_ += bad;
    for (int l : {0, 1, 2, 5, 6, 7})
      for (int i = 0; i < n; ++i)
        if (!std::isfinite(layer_[l][base + i])) layer_[l][base + i] = 0.0f;
    for (int i = 0; i < n; ++i)
      if (!std::isfinite(layer_[4][base + i])) layer_[4][base + i] = std::numeric_limits<float>::max();
    if (splatted)
      for (int c = 0; c < 3; ++c)
        for (int i = 0; i < n; ++i)
          if (!std::isfinite(p.spec[c][i])) p.spec[c][i] = 0.0f;
  }
  if (memory_) write_colour(p);
  if (visible_.empty()) return;
  for (int i = 0; i < p.count; ++i) {
    const size_t at = base + i;
    visible_[at] = splatted ? p.tri->source + 1 : 0;  // a nearer surface hides it
    if (splatted)
      for (int c = 0; c < 3; ++c) specular_[at * 3 + c] = p.spec[c][i];
  }
}

}  // namespace shadetlm::modules
