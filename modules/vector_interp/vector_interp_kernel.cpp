#include "modules/vector_interp/vector_interp_kernel.hpp"

#include <algorithm>

#include "modules/common/vector.hpp"

namespace modules {

VectorInterpKernel::VectorInterpKernel(const core::Scene& scene, const std::vector<int>& point_lights,
                                       bool affine_bump_vectors, core::NumberFormat format)
    : light_count_(int(std::min(scene.lights.size(), size_t(kMaxLights)))),
      world_(needed_in_world(scene)),
      affine_bump_vectors_(affine_bump_vectors),
      local_viewer_(scene.camera.local_viewer),
      numbers_(format) {
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
    if (i < size_t(kMaxLights)) writes_l_[i] = s.plane >= 0, writes_h_[i] = s.plane >= 0 || local_viewer_;
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

void VectorInterpKernel::process(SpanPacket& p) {
  const bool in_space = core::fetches_normal(p.tri->material->path);
  with_number_type(numbers_, [&](auto zero) {
    if (in_space) process_in_space<decltype(zero)>(p);
    else process_in_world<decltype(zero)>(p);
  });
  // Non-finite values among what was written: L and H of every light in the texture's
  // space; in the world, H of the lights listed and L of the point lights.
  for (int k = 0; k < light_count_; ++k)
    nonfinite_ += (in_space || writes_l_[k] ? count_nonfinite(p.l[k], p.count) : 0) +
                  (in_space || writes_h_[k] ? count_nonfinite(p.h[k], p.count) : 0);
  if (in_space) {
    ops_ += ops_per_pixel_in_space() * uint64_t(p.count);
    // Three plane seeds a vector: V and L (affine), or L and H, of every light.
    if (p.count > 0) ops_ += Ops{/*add*/ 6, /*mul*/ 6} * uint64_t(affine_bump_vectors_ ? light_count_ + 1 : 2 * light_count_);
  } else {
    ops_ += ops_per_pixel() * uint64_t(p.count);
    if (p.count > 0) ops_ += ops_per_span();
  }
}

// The planes are setup's, in float32; their seeds and steps are rounded to the format.
template <class T>
void VectorInterpKernel::process_in_space(SpanPacket& p) {
  const TriangleSetup& t = *p.tri;
  const int dx = p.x0 - t.x_ref, dy = p.y - t.y_ref;
  if (affine_bump_vectors_) {
    T view[kSpanMax][3];
    T v_w[3], v_step[3];
    for (int c = 0; c < 3; ++c) v_w[c] = T(t.vt[c].at(dx, dy)), v_step[c] = T(t.vt[c].ax);
    for (int i = 0; i < p.count; ++i) {
      const T w = T(p.w[i]);
      for (int c = 0; c < 3; ++c) view[i][c] = v_w[c] * w, v_w[c] += v_step[c];
      normalize3(view[i]);
    }
    for (int k = 0; k < light_count_; ++k) {
      T l_w[3], l_step[3];
      for (int c = 0; c < 3; ++c) {
        l_w[c] = T(t.lt[k][c].at(dx, dy)), l_step[c] = T(t.lt[k][c].ax);
        l_range_.add_span(t.lt[k][c].at(dx, dy), t.lt[k][c].ax, p.count, p.w);
      }
      for (int i = 0; i < p.count; ++i) {
        const T w = T(p.w[i]);
        T l[3];
        for (int c = 0; c < 3; ++c) l[c] = l_w[c] * w, l_w[c] += l_step[c];
        normalize3(l);
        T h[3] = {l[0] + view[i][0], l[1] + view[i][1], l[2] + view[i][2]};
        normalize3(h);
        for (int c = 0; c < 3; ++c) p.l[k][c][i] = float(l[c]), p.h[k][c][i] = float(h[c]);
      }
    }
    return;
  }
  for (int k = 0; k < light_count_; ++k) {
    T l_w[3], h_w[3], l_step[3], h_step[3];
    for (int c = 0; c < 3; ++c) {
      l_w[c] = T(t.lt[k][c].at(dx, dy)), h_w[c] = T(t.ht[k][c].at(dx, dy));
      l_step[c] = T(t.lt[k][c].ax), h_step[c] = T(t.ht[k][c].ax);
      l_range_.add_span(t.lt[k][c].at(dx, dy), t.lt[k][c].ax, p.count, p.w);
      h_range_.add_span(t.ht[k][c].at(dx, dy), t.ht[k][c].ax, p.count, p.w);
    }
    for (int i = 0; i < p.count; ++i) {
      const T w = T(p.w[i]);
      T l[3], h[3];
      for (int c = 0; c < 3; ++c) {
        l[c] = l_w[c] * w, h[c] = h_w[c] * w;
        l_w[c] += l_step[c], h_w[c] += h_step[c];
      }
      normalize3(l);
      normalize3(h);
      for (int c = 0; c < 3; ++c) p.l[k][c][i] = float(l[c]), p.h[k][c][i] = float(h[c]);
    }
  }
}

template <class T>
void VectorInterpKernel::process_in_world(SpanPacket& p) {
  const TriangleSetup& t = *p.tri;
  const int dx = p.x0 - t.x_ref, dy = p.y - t.y_ref;
  // Seeds of L/w and V/w at the packet's first pixel.
  T v_w[3], v_step[3];
  for (int c = 0; c < 3; ++c) v_w[c] = T(t.v[c].at(dx, dy)), v_step[c] = T(t.v[c].ax);
  T l_w[kMaxLights][3], l_step[kMaxLights][3];
  for (const auto& s : lights_)
    if (s.plane >= 0)
      for (int c = 0; c < 3; ++c) {
        const Plane& plane = t.l[s.plane][c];
        l_w[s.plane][c] = T(plane.at(dx, dy)), l_step[s.plane][c] = T(plane.ax);
        l_range_.add_span(plane.at(dx, dy), plane.ax, p.count, p.w);
      }

  for (int i = 0; i < p.count; ++i) {
    const T w = T(p.w[i]);
    T view[3] = {T(view_[0]), T(view_[1]), T(view_[2])};
    if (local_viewer_) {
      for (int c = 0; c < 3; ++c) view[c] = v_w[c] * w, v_w[c] += v_step[c];
      normalize3(view);
    }
    for (const auto& s : lights_) {
      T l[3] = {T(s.direction[0]), T(s.direction[1]), T(s.direction[2])};
      if (s.plane >= 0) {
        for (int c = 0; c < 3; ++c) l[c] = l_w[s.plane][c] * w, l_w[s.plane][c] += l_step[s.plane][c];
        normalize3(l);
        for (int c = 0; c < 3; ++c) p.l[s.light][c][i] = float(l[c]);
      }
      T h[3] = {l[0] + view[0], l[1] + view[1], l[2] + view[2]};
      normalize3(h);
      for (int c = 0; c < 3; ++c) p.h[s.light][c][i] = float(h[c]);
    }
  }
}

}  // namespace modules
