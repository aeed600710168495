#pragma once
// Triangle setup (normal-increments paper, "Setup, once per triangle"): for each
// triangle that survives clipping and covers a pixel, the plane equations of its
// attributes over the screen and the constant increments of the normal,
//
//   N2 − N1 = ΔN_H (x2 − x1) + ΔN_V (y2 − y1)
//   N3 − N1 = ΔN_H (x3 − x1) + ΔN_V (y3 − y1),     ΔN_D = ΔN_H + ΔN_V,
//
// solved per component with one shared reciprocal of the determinant; c = 2|ΔN_H|² for
// the forward-difference radicand. In perspective mode the same is done for N/w and
// 1/w. Vertex transformation, clipping and snapping follow core/coverage.hpp, the
// convention shared with the golden model, and are not counted as setup operations.
#include <functional>
#include <utility>
#include <vector>

#include "shadetlm/tlm/packet.hpp"

namespace shadetlm::modules {

// A plane through three vertices' values of one attribute, with the geometry terms
// shared by all the planes of a triangle. Written over the number type T so that a
// testbench can count its operations (ops_per_plane).
template <class T>
struct PlaneSolver {
  T dx1, dy1, dx2, dy2;  // vertex 2 and 3 relative to vertex 1, in pixels
  T inv_det;             // 1 / (dx1·dy2 − dx2·dy1)
  T ox, oy;              // the reference pixel's centre relative to vertex 1

  // Returns a0 (the value at the reference pixel), ax = ∂a/∂x, ay = ∂a/∂y.
  void solve(T a1, T a2, T a3, T& a0, T& ax, T& ay) const {
    const T da1 = a2 - a1, da2 = a3 - a1;
    ax = (da1 * dy2 - da2 * dy1) * inv_det;
    ay = (dx1 * da2 - dx2 * da1) * inv_det;
    a0 = a1 + ax * ox + ay * oy;
  }
};
constexpr Ops kOpsPerPlane{/*add*/ 6, /*mul*/ 8};

class SetupKernel {
 public:
  // affine_bump_vectors: vector_interp.bump_vectors = affine (docs/bump-mapping.md);
  // interpolate_h: vector_interp.h = interpolated (H's planes for the world-space paths).
  SetupKernel(const core::Scene& scene, bool perspective, bool affine_bump_vectors = false, bool interpolate_h = false);

  // Calls emit(const TriangleSetup&) for every triangle of the scene that covers a
  // pixel, in scene order (objects, then triangles, then clipped pieces).
  template <class Emit>
  void run(Emit&& emit);

  const Ops& ops() const { return ops_; }
  // Called with the share of the scene's triangles set up so far (0 … 1), every 1024.
  void set_progress(std::function<void(double)> progress) { progress_ = std::move(progress); }
  uint64_t triangles_in() const { return triangles_in_; }
  uint64_t triangles_out() const { return triangles_out_; }
  // The scene's triangles dropped (culled, clipped away, no pixel covered) since this was
  // last called: a triangle none of whose clipped pieces is handed on counts once.
  uint64_t take_rejected() { return std::exchange(rejected_, 0); }
  // Cycles setup's unit spends on a triangle it drops (setup.reject_cycles).
  uint64_t reject_cycles = 2;

 private:
  struct Vertex {  // a vertex of a clipped piece: exact (double) from the clipper
    glm::dvec2 screen;  // in pixels, exact (not snapped)
    double w;
    glm::dvec3 position, normal, tangent;
    glm::dvec2 uv;
  };
  bool setup(const Vertex v[3], const core::SnappedTriangle& coverage, TriangleSetup& out);
  // Parallax: eye − P in the relief's tangent space (docs/parallax.md).
  void setup_parallax(const Vertex v[3], const float inv_w[3], const PlaneSolver<float>& ps, TriangleSetup& t,
                      Ops& ops);
  // Bump-mapping planes (docs/bump-mapping.md); Pu, Pv of the whole triangle.
  void setup_bump(const Vertex v[3], const float inv_w[3], const PlaneSolver<float>& ps, glm::dvec3 pu,
                  glm::dvec3 pv, TriangleSetup& t, Ops& ops);
  // Its steps: the triangle's tangent frame, then the path's planes.
  struct BumpFrame {
    glm::dvec3 n[3];      // unit normals at the vertices
    glm::dvec3 pu, pv;    // ∂P/∂u, ∂P/∂v of the whole triangle
    double c = 0, s = 1;  // |Pu × Pv|, and −1 where the parameterization is mirrored
    bool exists = false;  // a frame: the uv triangle has area, the figures are in range
  };
  void setup_classic_bump(const BumpFrame& f, const float inv_w[3], const PlaneSolver<float>& ps, TriangleSetup& t,
                          Ops& ops);
  void texture_space(const Vertex v[3], const BumpFrame& f, core::ShadingPath path, glm::dmat3 to_space[3],
                     Ops& ops) const;
  void setup_affine_bump_vectors(const Vertex v[3], const glm::dmat3 to_space[3], const float inv_w[3],
                                 const PlaneSolver<float>& ps, TriangleSetup& t, Ops& ops) const;
  void setup_world_h(const Vertex v[3], const float inv_w[3], const PlaneSolver<float>& ps, TriangleSetup& t,
                     Ops& ops) const;
  void setup_unit_bump_vectors(const Vertex v[3], const BumpFrame& f, const glm::dmat3 to_space[3],
                               const float inv_w[3], const PlaneSolver<float>& ps, TriangleSetup& t, Ops& ops) const;

  const core::Scene& scene_;
  bool perspective_;
  bool affine_bump_vectors_;
  bool interpolate_h_;
  glm::dmat4 view_projection_;
  std::vector<int> point_lights_;
  bool local_viewer_;
  Ops ops_;
  uint64_t triangles_in_ = 0, triangles_out_ = 0, rejected_ = 0;
  TriangleSetup current_;
  std::function<void(double)> progress_;
  glm::dvec3 pu_{0}, pv_{0};      // of the current triangle (bump paths)
  glm::dmat3 to_object_{1.0};    // of the current object: world vectors into object space
};

template <class Emit>
void SetupKernel::run(Emit&& emit) {
  const int width = scene_.camera.width, height = scene_.camera.height;
  uint32_t id = 0, source = 0;
  uint64_t total = 0;
  for (const auto& object : scene_.objects) total += object.mesh.triangles.size();
  for (size_t o = 0; o < scene_.objects.size(); ++o) {
    const core::Object& object = scene_.objects[o];
    const core::Mesh mesh = core::to_world(object);
    current_.object = int(o);
    current_.material = &scene_.materials[object.material];
    const bool bump = core::bump_path(current_.material->path) || current_.material->path == core::ShadingPath::Parallax;
    // L and H in object space: n_world ∝ M⁻ᵀ n_object, so n_world·L = n_object·(M⁻¹ L).
    to_object_ = glm::inverse(glm::dmat3(object.model));
    for (const auto& t : mesh.triangles) {
      ++triangles_in_;
      current_.source = source++;
      if (progress_ && (source & 63) == 0) progress_(double(source) / double(total));
      const uint32_t idx[3] = {t.x, t.y, t.z};
      // A triangle with no area in space has no plane to interpolate on (the golden
      // model skips it too), even if snapping gives its screen image some area.
      const glm::dvec3 ng = glm::cross(mesh.positions[idx[1]] - mesh.positions[idx[0]],
                                       mesh.positions[idx[2]] - mesh.positions[idx[0]]);
      if (!(glm::dot(ng, ng) > 0)) {
        ++rejected_;
        continue;
      }
      if (bump) {  // P1 − P0 = Pu du1 + Pv dv1, P2 − P0 = Pu du2 + Pv dv2; zero without uv area
        const glm::dvec2 t1 = mesh.uvs[idx[1]] - mesh.uvs[idx[0]], t2 = mesh.uvs[idx[2]] - mesh.uvs[idx[0]];
        const glm::dvec3 e1 = mesh.positions[idx[1]] - mesh.positions[idx[0]];
        const glm::dvec3 e2 = mesh.positions[idx[2]] - mesh.positions[idx[0]];
        const double det = t1.x * t2.y - t2.x * t1.y;
        pu_ = det != 0 ? (e1 * t2.y - e2 * t1.y) / det : glm::dvec3(0);
        pv_ = det != 0 ? (e2 * t1.x - e1 * t2.x) / det : glm::dvec3(0);
      }
      glm::dvec4 clip[3];
      for (int k = 0; k < 3; ++k) clip[k] = view_projection_ * glm::dvec4(mesh.positions[idx[k]], 1.0);
      const auto poly = core::clip_triangle(clip[0], clip[1], clip[2]);
      bool handed = false;  // a piece of it handed on
      for (size_t p = 1; p + 1 < poly.size(); ++p) {
        const core::ClipVertex* cv[3] = {&poly[0], &poly[p], &poly[p + 1]};
        glm::dvec2 s[3];
        for (int k = 0; k < 3; ++k) s[k] = glm::dvec2(core::to_screen(cv[k]->clip, width, height));
        core::SnappedTriangle coverage;
        if (!core::snap_triangle(s[0], s[1], s[2], width, height, coverage)) continue;
        if (object.cull_back && !coverage.front_facing) continue;
        Vertex v[3];
        for (int k = 0; k < 3; ++k) {
          // The snapped triangle may have reordered its vertices.
          const core::ClipVertex& c = *cv[coverage.source[k]];
          const glm::dvec3 b = c.bary;
          // Attribute planes come from the exact positions; only coverage is snapped
          // (docs/pipeline.md: snapping the planes too tilts edge-on triangles).
          v[k].screen = s[coverage.source[k]];
          v[k].w = c.clip.w;
          v[k].position = b.x * mesh.positions[idx[0]] + b.y * mesh.positions[idx[1]] + b.z * mesh.positions[idx[2]];
          v[k].normal = b.x * mesh.normals[idx[0]] + b.y * mesh.normals[idx[1]] + b.z * mesh.normals[idx[2]];
          v[k].uv = b.x * mesh.uvs[idx[0]] + b.y * mesh.uvs[idx[1]] + b.z * mesh.uvs[idx[2]];
          v[k].tangent = b.x * glm::dvec3(mesh.tangents[idx[0]]) + b.y * glm::dvec3(mesh.tangents[idx[1]]) +
                         b.z * glm::dvec3(mesh.tangents[idx[2]]);
        }
        if (!setup(v, coverage, current_)) continue;
        current_.id = id++;
        ++triangles_out_;
        handed = true;
        emit(static_cast<const TriangleSetup&>(current_));
      }
      rejected_ += !handed;
    }
  }
}

}  // namespace shadetlm::modules
