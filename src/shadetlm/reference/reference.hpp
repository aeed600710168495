#pragma once
// The golden model: the exact answer the pipeline is measured against. Plain C++,
// double precision, no SystemC, and it never calls a pipeline kernel. It shares with
// the pipeline only conventions (the scene, core/coverage.hpp, texture addressing):
//
//  * coverage: core/coverage.hpp (clipping, 1/256-pixel snapping, top-left rule);
//  * visibility: a depth buffer of eye-space depth, nearer wins, ties keep the first;
//  * interpolation: the ray through the pixel centre meets the (unsnapped) triangle's
//    plane; the barycentric coordinates of that point are exactly the
//    perspective-correct ones;
//  * the normal is the barycentric mix of the vertex normals, normalized exactly;
//  * textures: one bilinear read of the finest level at the pixel's uv (phong); the
//    average of the texture over the pixel's footprint, 16×16 stratified samples, for
//    the texturing paths (texture-screen, texture-object);
//  * bump-mapped materials: Blinn's perturbed normal of the exact height field, with
//    the true per-pixel tangent frame (docs/bump-mapping.md);
//  * Blinn-Phong with every light (docs/golden-model.md).
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "shadetlm/core/frame.hpp"
#include "shadetlm/core/scene.hpp"

namespace shadetlm::reference {

// An allocator that leaves new elements of a trivial type uninitialized: the image's
// rows are first written by the threads that draw them (render), not all by one thread
// before (at 1080p the image is about 150 MB).
template <class T>
struct Uninitialized : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = Uninitialized<U>;
  };
  Uninitialized() = default;
  template <class U>
  Uninitialized(const Uninitialized<U>&) noexcept {}
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    if constexpr (sizeof...(Args) == 0) ::new (static_cast<void*>(p)) U;
    else ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};
template <class T>
using Buffer = std::vector<T, Uninitialized<T>>;

struct Image {
  int width = 0, height = 0;
  Buffer<glm::dvec3> color;   // linear RGB; the background where nothing is covered
  Buffer<double> alpha;       // 1 covered, 0 not
  Buffer<double> depth;       // eye-space depth; +inf where nothing is covered
  // The unit shading normal, in the space its path lights in: world (phong,
  // bump-classic), tangent (bump-tangent, bump-square), object (bump-object); 0 where
  // nothing is covered.
  Buffer<glm::dvec3> normal;
  // Where a scene has a parallax material: the exact hit of the view ray with the relief
  // (u, v, height in [0, 1]; the polygon's own uv and 1 where nothing is traced), 0 on
  // other surfaces and the background; written as parallax.u, .v, .height. Else empty.
  Buffer<glm::dvec3> hit;
  size_t index(int x, int y) const { return size_t(y) * width + x; }
};

// Blinn-Phong at world point P with unit normal N; `tex` is the colour texture's value
// there (1 without a texture), which modulates the ambient and diffuse terms.
glm::dvec3 shade(const core::Scene& scene, const core::Material& material, const glm::dvec3& P,
                 const glm::dvec3& N, const glm::dvec3& tex);

// `threads` (0: one per core) each draw every triangle into their own rows of the image
// (interleaved bands of kBandRows): every pixel sees the triangles in the same order, so
// the image is the same whatever the count.
Image render(const core::Scene& scene, int threads = 0);
constexpr int kBandRows = 4;

// What the golden model took as the truth where a scene gives it a choice, per material
// that objects use: for bump materials "height field" (Blinn's normal of the height
// map) or "normal map" (only a precomputed normal map given: read as the truth); for
// parallax "height field". Other materials are absent: their truth is the shading model.
std::map<std::string, std::string> truth(const core::Scene& scene);

// The image as an EXR frame (float channels R, G, B, A, Z, N.X, N.Y, N.Z, and
// parallax.u, .v, .height where it has hits), its layers converted by `threads` (0: one
// per core).
core::Frame to_frame(const Image& image, int threads = 0);

}  // namespace shadetlm::reference
