#include "modules/vector_interp/vector_interp_kernel.hpp"

#include <algorithm>

#include "modules/common/vector.hpp"

namespace modules {

VectorInterpKernel::VectorInterpKernel(const core::Scene& scene, const std::vector<int>& point_lights,
                                       bool affine_bump_vectors)
    : light_count_(int(std::min(scene.lights.size(), size_t(kMaxLights)))),
      world_(needed_in_world(scene)),
      affine_bump_vectors_(affine_bump_vectors),
      local_viewer_(scene.camera.local_viewer) {
  const glm::dvec3 v = -scene.camera.forward();
  for (int c = 0; c < 3; ++c) view_[c] = float(v[c]);
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    LightSlot s{int(i), -1, {0, 0, 0}};
    auto it = std::find(point_lights.begin(), point_lights.end(), int(i));
    if (it != point_lights.end()) s.plane = int(it - point_lights.begin());
    const glm::dvec3 l = -scene.lights[i].direction;
    for (int c = 0; c < 3; ++c) s.direction[c] = float(l[c]);
    // A directional light under a viewer at infinity has constant L and H: nothing here.
    if (s.plane >= 0 || local_viewer_) lights_.push_back(s);
  }
}

bool VectorInterpKernel::needed(const core::Scene& scene) {
  if (needed_in_world(scene)) return true;
  if (scene.lights.empty()) return false;
  for (const auto& o : scene.objects)
    if (core::fetches_normal(scene.materials[size_t(o.material)].path)) return true;
  return false;
}

bool VectorInterpKernel::needed_in_world(const core::Scene& scene) {
  if (scene.camera.local_viewer) return !scene.lights.empty();
  for (const auto& l : scene.lights)
    if (l.type == core::Light::Type::Point) return true;
  return false;
}

void VectorInterpKernel::trace(const SpanPacket& p, int i, double* out) const {
  if (core::fetches_normal(p.tri->material->path) || lights_.empty()) {  // light 0, in the texture's space
    for (int c = 0; c < 3; ++c) out[c] = p.l[0][c][i], out[3 + c] = p.h[0][c][i];
    return;
  }
  const LightSlot& s = lights_.front();
  for (int c = 0; c < 3; ++c) {
    out[c] = s.plane >= 0 ? p.l[s.light][c][i] : s.direction[c];
    out[3 + c] = p.h[s.light][c][i];
  }
}

Ops VectorInterpKernel::ops_per_pixel() const {
  Ops o;
  const Ops interpolate{/*add*/ 3, /*mul*/ 3};  // ×w, then one step of the plane
  if (local_viewer_) o += interpolate, o += kOpsNormalize3;
  for (const auto& s : lights_) {
    if (s.plane >= 0) o += interpolate, o += kOpsNormalize3;
    o += Ops{/*add*/ 3}, o += kOpsNormalize3;  // H = normalize(L̂ + V̂)
  }
  return o;
}

Ops VectorInterpKernel::ops_per_span() const {
  int vectors = local_viewer_ ? 1 : 0;
  for (const auto& s : lights_) vectors += s.plane >= 0;
  return Ops{/*add*/ 6, /*mul*/ 6} * uint64_t(vectors);  // three plane seeds each
}

Ops VectorInterpKernel::ops_per_pixel_in_space() const {
  const Ops interpolate{/*add*/ 3, /*mul*/ 3};  // ×w, then one step of the plane
  if (affine_bump_vectors_)  // V once; per light L, then H = normalize(L̂ + V̂)
    return interpolate + kOpsNormalize3 + (interpolate + kOpsNormalize3 * 2 + Ops{/*add*/ 3}) * uint64_t(light_count_);
  return (interpolate + kOpsNormalize3) * uint64_t(2 * light_count_);
}

void VectorInterpKernel::process_in_space(SpanPacket& p) {
  const TriangleSetup& t = *p.tri;
  const int dx = p.x0 - t.x_ref, dy = p.y - t.y_ref;
  if (affine_bump_vectors_) {
    float view[kSpanMax][3];
    float v_w[3];
    for (int c = 0; c < 3; ++c) v_w[c] = t.vt[c].at(dx, dy);
    for (int i = 0; i < p.count; ++i) {
      for (int c = 0; c < 3; ++c) view[i][c] = v_w[c] * p.w[i], v_w[c] += t.vt[c].ax;
      normalize3(view[i]);
    }
    for (int k = 0; k < light_count_; ++k) {
      float l_w[3];
      for (int c = 0; c < 3; ++c) {
        l_w[c] = t.lt[k][c].at(dx, dy);
        l_range_.add_span(l_w[c], t.lt[k][c].ax, p.count, p.w);
      }
      for (int i = 0; i < p.count; ++i) {
        float l[3];
        for (int c = 0; c < 3; ++c) l[c] = l_w[c] * p.w[i], l_w[c] += t.lt[k][c].ax;
        normalize3(l);
        float h[3] = {l[0] + view[i][0], l[1] + view[i][1], l[2] + view[i][2]};
        normalize3(h);
        for (int c = 0; c < 3; ++c) p.l[k][c][i] = l[c], p.h[k][c][i] = h[c];
      }
    }
    ops_ += ops_per_pixel_in_space() * uint64_t(p.count);
    if (p.count > 0) ops_ += Ops{/*add*/ 6, /*mul*/ 6} * uint64_t(light_count_ + 1);  // three plane seeds a vector
    return;
  }
  for (int k = 0; k < light_count_; ++k) {
    float l_w[3], h_w[3];
    for (int c = 0; c < 3; ++c) {
      l_w[c] = t.lt[k][c].at(dx, dy), h_w[c] = t.ht[k][c].at(dx, dy);
      l_range_.add_span(l_w[c], t.lt[k][c].ax, p.count, p.w);
      h_range_.add_span(h_w[c], t.ht[k][c].ax, p.count, p.w);
    }
    for (int i = 0; i < p.count; ++i) {
      const float w = p.w[i];
      float l[3], h[3];
      for (int c = 0; c < 3; ++c) {
        l[c] = l_w[c] * w, h[c] = h_w[c] * w;
        l_w[c] += t.lt[k][c].ax, h_w[c] += t.ht[k][c].ax;
      }
      normalize3(l);
      normalize3(h);
      for (int c = 0; c < 3; ++c) p.l[k][c][i] = l[c], p.h[k][c][i] = h[c];
    }
  }
  ops_ += ops_per_pixel_in_space() * uint64_t(p.count);
  if (p.count > 0) ops_ += Ops{/*add*/ 12, /*mul*/ 12} * uint64_t(light_count_);  // six plane seeds a light
}

void VectorInterpKernel::process(SpanPacket& p) {
  if (core::fetches_normal(p.tri->material->path)) return process_in_space(p);
  const TriangleSetup& t = *p.tri;
  const int dx = p.x0 - t.x_ref, dy = p.y - t.y_ref;
  // Seeds of L/w and V/w at the packet's first pixel.
  float v_w[3], v_step[3];
  for (int c = 0; c < 3; ++c) v_w[c] = t.v[c].at(dx, dy), v_step[c] = t.v[c].ax;
  float l_w[kMaxLights][3], l_step[kMaxLights][3];
  for (const auto& s : lights_)
    if (s.plane >= 0)
      for (int c = 0; c < 3; ++c) {
        l_w[s.plane][c] = t.l[s.plane][c].at(dx, dy), l_step[s.plane][c] = t.l[s.plane][c].ax;
        l_range_.add_span(l_w[s.plane][c], l_step[s.plane][c], p.count, p.w);
      }

  for (int i = 0; i < p.count; ++i) {
    const float w = p.w[i];
    float view[3] = {view_[0], view_[1], view_[2]};
    if (local_viewer_) {
      for (int c = 0; c < 3; ++c) view[c] = v_w[c] * w, v_w[c] += v_step[c];
      normalize3(view);
    }
    for (const auto& s : lights_) {
      float l[3] = {s.direction[0], s.direction[1], s.direction[2]};
      if (s.plane >= 0) {
        for (int c = 0; c < 3; ++c) l[c] = l_w[s.plane][c] * w, l_w[s.plane][c] += l_step[s.plane][c];
        normalize3(l);
        for (int c = 0; c < 3; ++c) p.l[s.light][c][i] = l[c];
      }
      float h[3] = {l[0] + view[0], l[1] + view[1], l[2] + view[2]};
      normalize3(h);
      for (int c = 0; c < 3; ++c) p.h[s.light][c][i] = h[c];
    }
  }
  ops_ += ops_per_pixel() * uint64_t(p.count);
  if (p.count > 0) ops_ += ops_per_span();
}

}  // namespace modules
