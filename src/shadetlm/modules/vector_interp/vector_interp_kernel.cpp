#include "shadetlm/modules/vector_interp/vector_interp_kernel.hpp"

#include <algorithm>
#include <type_traits>

#include "shadetlm/numeric/vector.hpp"

namespace shadetlm::modules {

VectorInterpKernel::VectorInterpKernel(const core::Scene& scene, const std::vector<int>& point_lights,
                                       bool affine_bump_vectors, core::NumberFormat format, bool interpolate_h)
    : light_count_(int(std::min(scene.lights.size(), size_t(kMaxLights)))),
      world_(needed_in_world(scene)),
      affine_bump_vectors_(affine_bump_vectors),
      interpolate_h_(interpolate_h),
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
  if (local_viewer_ && !interpolate_h_) o += interpolate, o += kOpsNormalize3;
  for (const auto& s : lights_) {
    if (s.plane >= 0) o += interpolate, o += kOpsNormalize3;
    if (interpolate_h_) o += interpolate, o += kOpsNormalize3;  // H from its plane
    else o += Ops{/*add*/ 3}, o += kOpsNormalize3;              // H = normalize(L̂ + V̂)
  }
  return o;
}

Ops VectorInterpKernel::ops_per_span() const {
  int vectors = local_viewer_ && !interpolate_h_ ? 1 : 0;
  for (const auto& s : lights_) vectors += (s.plane >= 0) + interpolate_h_;
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
  tally_.add(in_space ? 1 : 0, p.count);
}

Ops VectorInterpKernel::ops() const {
  // In the texture's space, three plane seeds a vector: V and L (affine), or L and H, of
  // every light.
  const Ops seeds_in_space = Ops{/*add*/ 6, /*mul*/ 6} * uint64_t(affine_bump_vectors_ ? light_count_ + 1 : 2 * light_count_);
  return ops_per_pixel() * tally_.pixels[0] + ops_per_span() * tally_.packets[0] +
         ops_per_pixel_in_space() * tally_.pixels[1] + seeds_in_space * tally_.packets[1];
}

// The planes are setup's, in float32; their seeds and steps are rounded to the format.
template <class T>
void VectorInterpKernel::process_in_space(SpanPacket& p) {
  const TriangleSetup& t = *p.tri;
  const int dx = p.x0 - t.x_ref, dy = p.y - t.y_ref;
  if (affine_bump_vectors_) {
    T view[kSpanMax][3];
    T v_w[3], v_step[3];
    for (int c = 0; c < 3; ++c) v_w[c] = plane_seed<T>(t.vt[c], dx, dy), v_step[c] = T(t.vt[c].ax);
    for (int i = 0; i < p.count; ++i) {
      const T w = T(p.w[i]);
      for (int c = 0; c < 3; ++c) view[i][c] = v_w[c] * w, v_w[c] += v_step[c];
      normalize3(view[i]);
    }
    for (int k = 0; k < light_count_; ++k) {
      T l_w[3], l_step[3];
      for (int c = 0; c < 3; ++c) {
        l_w[c] = plane_seed<T>(t.lt[k][c], dx, dy), l_step[c] = T(t.lt[k][c].ax);
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
      l_w[c] = plane_seed<T>(t.lt[k][c], dx, dy), h_w[c] = plane_seed<T>(t.ht[k][c], dx, dy);
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
  // float32 in whole groups of lanes (kLanes: no scalar tails), the other formats pixel
  // by pixel.
  const int count = std::is_same_v<T, float> ? lanes(p.count) : p.count;
  // A vector over w, stepped along the span from its seed at the packet's first pixel by
  // the constant increment: a chain of additions, in a loop of its own …
  auto step_along = [&](const Plane plane[3], T out[3][kSpanMax]) {
    for (int c = 0; c < 3; ++c) {
      T a = plane_seed<T>(plane[c], dx, dy);
      const T step = T(plane[c].ax);
      for (int i = 0; i < count; ++i) out[c][i] = a, a += step;
    }
  };
  // … then ×w and normalized, pixel by pixel: a straight loop, which vectorizes.
  auto unit_times_w = [&](T v[3][kSpanMax]) {
    for (int i = 0; i < count; ++i) {
      const T w = T(p.w[i]);
      T u[3] = {v[0][i] * w, v[1][i] * w, v[2][i] * w};
      normalize3(u);
      v[0][i] = u[0], v[1][i] = u[1], v[2][i] = u[2];
    }
  };
  T view[3][kSpanMax];
  if (interpolate_h_) {
    // (no V: H comes from its own plane)
  } else if (local_viewer_) {
    step_along(t.v, view);
    unit_times_w(view);
  } else {
    for (int c = 0; c < 3; ++c)
      for (int i = 0; i < count; ++i) view[c][i] = T(view_[c]);
  }
  T l_regs[3][kSpanMax], h_regs[3][kSpanMax];  // other formats: the format's registers
  for (const auto& s : lights_) {
    // float32 writes the packet's wires straight: H, and L of a point light (a
    // directional light's L stays a constant, in a register).
    T(*l)[kSpanMax] = l_regs;
    T(*h)[kSpanMax] = h_regs;
    if constexpr (std::is_same_v<T, float>) {
      h = p.h[s.light];
      if (s.plane >= 0) l = p.l[s.light];
    }
    if (s.plane >= 0) {
      for (int c = 0; c < 3; ++c) l_range_.add_span(t.l[s.plane][c].at(dx, dy), t.l[s.plane][c].ax, p.count, p.w);
      step_along(t.l[s.plane], l);
      unit_times_w(l);
    } else {
      for (int c = 0; c < 3; ++c)
        for (int i = 0; i < count; ++i) l[c][i] = T(s.direction[c]);
    }
    if (interpolate_h_) {  // H at the vertices, interpolated, normalized (Fig. 1)
      for (int c = 0; c < 3; ++c) h_range_.add_span(t.ht[s.light][c].at(dx, dy), t.ht[s.light][c].ax, p.count, p.w);
      step_along(t.ht[s.light], h);
      unit_times_w(h);
    } else {
      for (int i = 0; i < count; ++i) {  // H = normalize(L̂ + V̂)
        T u[3] = {l[0][i] + view[0][i], l[1][i] + view[1][i], l[2][i] + view[2][i]};
        normalize3(u);
        h[0][i] = u[0], h[1][i] = u[1], h[2][i] = u[2];
      }
    }
    if constexpr (!std::is_same_v<T, float>)
      for (int c = 0; c < 3; ++c)
        for (int i = 0; i < count; ++i) {
          if (s.plane >= 0) p.l[s.light][c][i] = float(l[c][i]);
          p.h[s.light][c][i] = float(h[c][i]);
        }
  }
}

}  // namespace shadetlm::modules
