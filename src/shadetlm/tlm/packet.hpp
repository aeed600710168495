#pragma once
// What travels between the blocks: per triangle, its setup (plane equations and
// increments); per span, a packet of up to kSpanMax visible pixels of one raster row
// of one triangle, in structure-of-arrays form, filled in block by block.
#include <algorithm>
#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

#include "shadetlm/core/coverage.hpp"
#include "shadetlm/core/scene.hpp"
#include "shadetlm/numeric/ops.hpp"

namespace shadetlm::modules {

constexpr int kSpanMax = 64;   // pixels per packet
constexpr int kMaxLights = 8;  // lights the lighting datapath holds

// The float32 kernels' vector width: a kernel may compute a packet in whole groups of
// kLanes pixels, the lanes past `count` on whatever an array holds there (values of an
// earlier packet, or 0: the raster's packet starts zeroed), and nobody reads them. A
// short span (15 pixels on average on a sphere) then runs no scalar tail loop.
constexpr int kLanes = 4;
static_assert(kSpanMax % kLanes == 0, "whole groups of lanes fit in a packet");
inline int lanes(int count) { return (count + kLanes - 1) / kLanes * kLanes; }

// An attribute as a plane over the screen, in pixel steps from the triangle's
// reference pixel: a(x, y) = a0 + ax·(x − x_ref) + ay·(y − y_ref).
struct Plane {
  float a0 = 0, ax = 0, ay = 0;
  float at(int dx, int dy) const { return a0 + ax * float(dx) + ay * float(dy); }
};

// A plane's value at a packet's first pixel as a datapath of type T receives it: the
// seed (2 multiplications, 2 additions) in float32, rounded to T; the seed's operations
// tallied when T counts them.
template <class T>
T plane_seed(const Plane& p, int dx, int dy) {
  count_discarded<T>(Ops{/*add*/ 2, /*mul*/ 2});
  return T(p.at(dx, dy));
}

// The material of a triangle made without a scene (testbenches): plain Phong.
inline const core::Material kDefaultMaterial{};

// The point lights of a scene, in the order of TriangleSetup's light slots (slot k of
// TriangleSetup::l is light point_lights(scene)[k]).
inline std::vector<int> point_lights(const core::Scene& scene) {
  std::vector<int> lights;
  for (size_t i = 0; i < scene.lights.size(); ++i)
    if (scene.lights[i].type == core::Light::Type::Point) lights.push_back(int(i));
  return lights;
}

struct TriangleSetup {
  uint32_t id = 0;                     // running number in the frame
  uint32_t source = 0;                 // the scene triangle it comes from (all objects' triangles, in order)
  int object = 0;
  const core::Material* material = &kDefaultMaterial;
  core::SnappedTriangle coverage;      // the shared coverage convention
  int x_ref = 0, y_ref = 0;            // reference pixel: leftmost of the top covered row

  Plane inv_w;                         // 1/w, affine on screen
  float inv_w_min = 0;                 // the smallest 1/w of the vertices (> 0)
  // The normal: N (affine mode) or N/w (perspective mode). n[k].ax and n[k].ay are the
  // paper's constant increments ΔN_H and ΔN_V; n[k].a0 is the seed at the reference pixel.
  Plane n[3];
  float dn_d[3] = {0, 0, 0};           // ΔN_D = ΔN_H + ΔN_V: a step down and right
  float dn_a[3] = {0, 0, 0};           // ΔN_A = ΔN_V − ΔN_H: a step down and left
  float c = 0;                         // 2·|ΔN_H|², the radicand's second difference
  Plane l[kMaxLights][3];              // (light position − P)/w, point lights
  Plane v[3];                          // (eye − P)/w, local viewer
  Plane uv[2];                         // uv/w (colour texture or bump map)
  // Bump mapping (docs/bump-mapping.md). Fetched-normal paths: L and H of every light
  // transformed into the texture's space (tangent or object) at the vertices, over w.
  // With vector_interp.bump_vectors = affine: L = light − P (or the unit direction) and
  // V = eye − P (or the unit view direction) instead, H formed per pixel (vt holds V).
  Plane lt[kMaxLights][3], ht[kMaxLights][3];
  Plane vt[3];
  // Classic path (Fig. 2): n × Pv and Pu × n over w, and c = |Pu × Pv| (1 and zero
  // vectors where the uv triangle has no area: no tangent frame, no perturbation).
  Plane n_x_pv[3], pu_x_n[3];
  // Parallax: eye − P in the relief's tangent space (along Pu, Pv, and the normal scaled
  // to uv units), over w; no frame where the uv triangle has no area.
  Plane eye_t[3];
  bool parallax_frame = false;
  float bump_c = 1;
  bool bump_frame = true;  // false: no Pu, Pv (uv without area): the normal is not perturbed
};

struct SpanPacket {
  const TriangleSetup* tri = nullptr;
  int y = 0;          // raster row
  int x0 = 0;         // first pixel of this packet
  int count = 0;      // visible pixels x0 … x0 + count − 1
  int row_start = 0;  // first covered pixel of the row (where the edge walker stands)

  float inv_w[kSpanMax];  // raster: 1/w
  float w[kSpanMax];      // raster: w, the eye-space depth
  float n[3][kSpanMax];   // normal_interp, then normalize: the normal
  float l[kMaxLights][3][kSpanMax];  // vector_interp: unit L (point lights)
  float h[kMaxLights][3][kSpanMax];  // vector_interp: unit H (point lights or local viewer)
  float bump[3][kSpanMax]; // bump_fetch: the filtered normal N' (fetched paths) or Fu, Fv (classic)
  float uvp[2][kSpanMax];  // parallax: uv where the view ray meets the relief
  float iterations[kSpanMax];  // parallax: the tracer's iterations
  float hit_height[kSpanMax];  // parallax: the relief's height (0 … 1) at uvp, 1 where untraced
  float tex[3][kSpanMax]; // texture_fetch: colour texture
  float rgb[3][kSpanMax]; // lighting (texture-object: the ambient and diffuse factor D)
  float spec[3][kSpanMax]; // lighting, texture-object only: the specular term S (C = tex ⊙ D + S later)
};

// A block's work for each pixel of a packet, in units of its II (a kernel's work()):
// uniform (`each`, and `lead` more for the packet's first pixel: a seed, a walk to it) or
// per pixel. 0: no work (bypassed). A memory client also says how many cache lines each
// pixel moved to or from the DRAM (`lines`; none: null).
struct Work {
  const uint16_t* per_pixel = nullptr;
  uint32_t each = 0;
  const uint16_t* lines = nullptr;
  uint32_t lead = 0;
  uint32_t lines_at(int i) const { return lines ? lines[i] : 0; }
  // A uniform block's first pixel: its lead too (at most 65535, as a per-pixel array holds).
  uint32_t first() const { return std::min<uint32_t>(each + lead, 65535); }
  uint32_t at(int i) const { return per_pixel ? per_pixel[i] : i == 0 ? first() : each; }
};

class FramebufferKernel;

// The end of a pass, a transaction of its own (command TLM_IGNORE_COMMAND and a data
// length of sizeof(PassEnd), where span packets and triangles are writes) that follows the pass's last packet through every
// block. It starts the next pass (texel_project's splat pass after the main chain) and
// carries what that pass needs from this one.
struct PassEnd {
  uint64_t cycle = 0;  // when every block of the pass so far has put out its last result
  FramebufferKernel* framebuffer = nullptr;  // set by the framebuffer: the frame so far
};
// Kernels that hand something on at the end of a pass have end_pass(PassEnd&).
template <class K, class = void> struct has_end_pass : std::false_type {};
template <class K>
struct has_end_pass<K, std::void_t<decltype(std::declval<K&>().end_pass(std::declval<PassEnd&>()))>>
    : std::true_type {};

}  // namespace shadetlm::modules
