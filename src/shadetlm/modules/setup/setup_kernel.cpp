#include "shadetlm/modules/setup/setup_kernel.hpp"

#include <algorithm>
#include <cmath>

#include "shadetlm/numeric/vector.hpp"

namespace shadetlm::modules {

SetupKernel::SetupKernel(const core::Scene& scene, bool perspective, bool affine_bump_vectors, bool interpolate_h)
    : scene_(scene),
      perspective_(perspective),
      affine_bump_vectors_(affine_bump_vectors),
      interpolate_h_(interpolate_h),
      view_projection_(scene.camera.projection() * scene.camera.view()),
      point_lights_(modules::point_lights(scene)),
      local_viewer_(scene.camera.local_viewer) {}

bool SetupKernel::setup(const Vertex v[3], const core::SnappedTriangle& coverage, TriangleSetup& t) {
  // The reference pixel: the leftmost covered pixel of the top covered row.
  bool found = false;
  for (int y = coverage.y0; y <= coverage.y1 && !found; ++y) {
    const auto [x_begin, x_end] = coverage.row_span(y);
    if (x_begin < x_end) {
      t.x_ref = x_begin;
      t.y_ref = y;
      found = true;
    }
  }
  if (!found) return false;
  t.coverage = coverage;

  PlaneSolver<float> ps;
  // Differences in double, then float: the planes keep float's relative precision.
  ps.dx1 = float(v[1].screen.x - v[0].screen.x);
  ps.dy1 = float(v[1].screen.y - v[0].screen.y);
  ps.dx2 = float(v[2].screen.x - v[0].screen.x);
  ps.dy2 = float(v[2].screen.y - v[0].screen.y);
  const float det = ps.dx1 * ps.dy2 - ps.dx2 * ps.dy1;
  if (!(det != 0 && std::isfinite(det))) return false;  // no plane through the pixels
  ps.inv_det = 1.0f / det;
  ps.ox = float(t.x_ref + 0.5 - v[0].screen.x);
  ps.oy = float(t.y_ref + 0.5 - v[0].screen.y);
  // Four differences, the determinant (2 mul, 1 add), its reciprocal, two offsets.
  Ops ops{/*add*/ 7, /*mul*/ 2, /*div*/ 1};

  // Attributes at the vertices, divided by w where interpolation is perspective-correct.
  float inv_w[3];
  for (int k = 0; k < 3; ++k) inv_w[k] = float(1.0 / v[k].w);
  ops.div += 3;
  auto plane = [&](Plane& p, float a1, float a2, float a3) {
    ps.solve(a1, a2, a3, p.a0, p.ax, p.ay);
    ops += kOpsPerPlane;
  };
  auto perspective_plane = [&](Plane& p, double a1, double a2, double a3) {
    plane(p, float(a1) * inv_w[0], float(a2) * inv_w[1], float(a3) * inv_w[2]);
    ops.mul += 3;
  };
  plane(t.inv_w, inv_w[0], inv_w[1], inv_w[2]);
  t.inv_w_min = std::min({inv_w[0], inv_w[1], inv_w[2]});
  for (int c = 0; c < 3; ++c) {
    if (perspective_)
      perspective_plane(t.n[c], v[0].normal[c], v[1].normal[c], v[2].normal[c]);
    else
      plane(t.n[c], float(v[0].normal[c]), float(v[1].normal[c]), float(v[2].normal[c]));
    t.dn_d[c] = t.n[c].ax + t.n[c].ay;
    t.dn_a[c] = t.n[c].ay - t.n[c].ax;
  }
  t.c = 2.0f * (t.n[0].ax * t.n[0].ax + t.n[1].ax * t.n[1].ax + t.n[2].ax * t.n[2].ax);
  ops.add += 6 + 2;
  ops.mul += 4;

  // L = light − P and V = eye − P are affine over the triangle in world space, so
  // their perspective-correct interpolation is exact.
  for (size_t k = 0; k < point_lights_.size() && k < size_t(kMaxLights); ++k) {
    const glm::dvec3 lp = scene_.lights[point_lights_[k]].position;
    for (int c = 0; c < 3; ++c)
      perspective_plane(t.l[k][c], lp[c] - v[0].position[c], lp[c] - v[1].position[c],
                        lp[c] - v[2].position[c]);
  }
  if (local_viewer_) {
    const glm::dvec3 eye = scene_.camera.position;
    for (int c = 0; c < 3; ++c)
      perspective_plane(t.v[c], eye[c] - v[0].position[c], eye[c] - v[1].position[c],
                        eye[c] - v[2].position[c]);
  }
  // uv planes for the texture unit (texture-object reads uv in texel_project instead).
  if ((t.material->texture >= 0 && t.material->path != core::ShadingPath::TextureObject) ||
      core::bump_path(t.material->path) || t.material->path == core::ShadingPath::Parallax)
    for (int c = 0; c < 2; ++c) perspective_plane(t.uv[c], v[0].uv[c], v[1].uv[c], v[2].uv[c]);
  if (core::bump_path(t.material->path)) setup_bump(v, inv_w, ps, pu_, pv_, t, ops);
  if (t.material->path == core::ShadingPath::Parallax) setup_parallax(v, inv_w, ps, t, ops);
  if (interpolate_h_ && !core::fetches_normal(t.material->path)) setup_world_h(v, inv_w, ps, t, ops);
  ops_ += ops;
  return true;
}

void SetupKernel::setup_parallax(const Vertex v[3], const float inv_w[3], const PlaneSolver<float>& ps,
                                 TriangleSetup& t, Ops& ops) {
  // The relief's frame: Pu, Pv and the normal on the side of the vertex normals, scaled
  // to the length of one uv unit, L = √|Pu × Pv| (docs/parallax.md). eye − P is affine
  // over the triangle, so its tangent-space planes over w are exact.
  const glm::dvec3 pu_x_pv = glm::cross(pu_, pv_);
  const double area = glm::length(pu_x_pv);
  const glm::dvec3 normals = v[0].normal + v[1].normal + v[2].normal;
  const glm::dvec3 n = (glm::dot(pu_x_pv, normals) < 0 ? -1.0 : 1.0) * pu_x_pv / area * std::sqrt(area);
  const glm::dmat3 frame(pu_, pv_, n);
  const double det = glm::determinant(frame);
  t.parallax_frame = area > 0 && std::isfinite(float(area)) && det != 0 && std::isfinite(det);
  if (!t.parallax_frame) return;
  const glm::dmat3 to_tangent = glm::inverse(frame);
  const glm::dvec3 eye = scene_.camera.position;
  glm::dvec3 e[3];
  for (int k = 0; k < 3; ++k) e[k] = to_tangent * (eye - v[k].position);
  for (int c = 0; c < 3; ++c)
    ps.solve(float(e[0][c]) * inv_w[0], float(e[1][c]) * inv_w[1], float(e[2][c]) * inv_w[2], t.eye_t[c].a0,
             t.eye_t[c].ax, t.eye_t[c].ay);
  // The frame and its inverse (about 40 mul, 25 add, 1 div, 2 sqrt), three vectors into
  // it (27 mul, 27 add), three planes.
  ops += kOpsPerPlane * 3 + Ops{/*add*/ 25 + 27, /*mul*/ 40 + 27 + 9, /*div*/ 1, /*sqrt*/ 2};
}

namespace {
// Values at the vertices, over w, as planes (as setup() does for the others).
void solve_planes(const PlaneSolver<float>& ps, const float inv_w[3], Plane out[3], const glm::dvec3 value[3],
                  Ops& ops) {
  for (int c = 0; c < 3; ++c)
    ps.solve(float(value[0][c]) * inv_w[0], float(value[1][c]) * inv_w[1], float(value[2][c]) * inv_w[2], out[c].a0,
             out[c].ax, out[c].ay);
  ops += kOpsPerPlane * 3;
  ops.mul += 9;
}
}  // namespace

// Fig. 1's H: H = normalize(L̂ + V̂) at the vertices, of every light whose H is not a
// constant (a point light, or any light under a local viewer), as planes over w.
void SetupKernel::setup_world_h(const Vertex v[3], const float inv_w[3], const PlaneSolver<float>& ps,
                                TriangleSetup& t, Ops& ops) const {
  const core::Camera& cam = scene_.camera;
  for (size_t light = 0; light < scene_.lights.size() && light < size_t(kMaxLights); ++light) {
    const core::Light& l = scene_.lights[light];
    const bool point = l.type == core::Light::Type::Point;
    if (!point && !local_viewer_) continue;
    glm::dvec3 hv[3];
    for (int k = 0; k < 3; ++k) {
      glm::dvec3 L = -l.direction, V = -cam.forward();
      if (point) L = l.position - v[k].position, ops += Ops{/*add*/ 3};
      if (local_viewer_) V = cam.position - v[k].position, ops += Ops{/*add*/ 3};
      L = glm::dot(L, L) > 0 ? glm::normalize(L) : v[k].normal;
      V = glm::dot(V, V) > 0 ? glm::normalize(V) : v[k].normal;
      const glm::dvec3 h = L + V;
      hv[k] = glm::dot(h, h) > 0 ? glm::normalize(h) : v[k].normal;
      ops += Ops{/*add*/ 3} + kOpsNormalize3 * uint64_t(1 + point + local_viewer_);
    }
    solve_planes(ps, inv_w, t.ht[light], hv, ops);
  }
}

void SetupKernel::setup_bump(const Vertex v[3], const float inv_w[3], const PlaneSolver<float>& ps,
                             glm::dvec3 pu, glm::dvec3 pv, TriangleSetup& t, Ops& ops) {
  BumpFrame f;
  for (int k = 0; k < 3; ++k) f.n[k] = glm::normalize(v[k].normal);
  ops += kOpsNormalize3 * 3;
  f.pu = pu, f.pv = pv;
  // The triangle's tangent frame, from Pu and Pv (solved in run(): about 20 mul, 17 add,
  // 1 div), and its orientation: s = −1 where the parameterization is mirrored against
  // the shading normal, so that the relief stays a relief (N' = c·n + s·(…)). No frame
  // where the uv triangle has no area or the figures leave float's range.
  const glm::dvec3 pu_x_pv = glm::cross(pu, pv);
  f.c = glm::length(pu_x_pv);
  f.exists = f.c > 0 && std::isfinite(float(f.c)) && std::isfinite(float(glm::length(pu))) &&
             std::isfinite(float(glm::length(pv)));
  f.s = glm::dot(pu_x_pv, f.n[0] + f.n[1] + f.n[2]) < 0 ? -1.0 : 1.0;
  t.bump_frame = f.exists;
  ops += Ops{/*add*/ 17 + 5 + 8, /*mul*/ 20 + 9 + 3, /*div*/ 1, /*sqrt*/ 1};
  if (t.material->path == core::ShadingPath::BumpClassic) return setup_classic_bump(f, inv_w, ps, t, ops);
  glm::dmat3 to_space[3];
  texture_space(v, f, t.material->path, to_space, ops);
  if (affine_bump_vectors_) setup_affine_bump_vectors(v, to_space, inv_w, ps, t, ops);
  else setup_unit_bump_vectors(v, f, to_space, inv_w, ps, t, ops);
}

// Classic bump mapping: the planes of n × Pv and Pu × n (signed by s), and c = |Pu × Pv|.
void SetupKernel::setup_classic_bump(const BumpFrame& f, const float inv_w[3], const PlaneSolver<float>& ps,
                                     TriangleSetup& t, Ops& ops) {
  glm::dvec3 x[3], y[3];
  for (int k = 0; k < 3; ++k) {
    x[k] = f.exists ? f.s * glm::cross(f.n[k], f.pv) : glm::dvec3(0);
    y[k] = f.exists ? f.s * glm::cross(f.pu, f.n[k]) : glm::dvec3(0);
  }
  t.bump_c = f.exists ? float(f.c) : 1.0f;  // no tangent frame: N unperturbed
  solve_planes(ps, inv_w, t.n_x_pv, x, ops);
  solve_planes(ps, inv_w, t.pu_x_n, y, ops);
  ops += Ops{/*add*/ 18, /*mul*/ 36 + 18};  // two cross products per vertex, the sign
}

// Fetched-normal paths: the texture's space at each vertex — tangent (rows T, B, n) or
// object (to_object_). The tangent T is the map's, Pu on the tangent plane (so the
// frames agree at the vertices); B = n × T, turned by s for the square patch, whose b
// runs along Pv. Without a frame, bump_fetch sends the unperturbed normal +z and the
// lighting is done in a tangent frame.
void SetupKernel::texture_space(const Vertex v[3], const BumpFrame& f, core::ShadingPath path,
                                glm::dmat3 to_space[3], Ops& ops) const {
  for (int k = 0; k < 3; ++k) {
    if (path == core::ShadingPath::BumpObject && f.exists) {
      to_space[k] = to_object_;
      continue;
    }
    const glm::dvec3 along = f.exists ? f.pu : v[k].tangent;
    glm::dvec3 T = along - glm::dot(along, f.n[k]) * f.n[k];
    T = glm::dot(T, T) > 1e-24 ? glm::normalize(T) : core::any_tangent(f.n[k]);
    const glm::dvec3 B = (path == core::ShadingPath::BumpSquare ? f.s : 1.0) * glm::cross(f.n[k], T);
    to_space[k] = glm::transpose(glm::dmat3(T, B, f.n[k]));  // rows T, B, n
    ops += Ops{/*add*/ 2 + 3 + 3, /*mul*/ 3 + 3 + 6} + kOpsNormalize3;
  }
}

// vector_interp.bump_vectors = affine: L = light − P and V = eye − P, affine over the
// triangle, in the space of each vertex, as planes.
void SetupKernel::setup_affine_bump_vectors(const Vertex v[3], const glm::dmat3 to_space[3], const float inv_w[3],
                                            const PlaneSolver<float>& ps, TriangleSetup& t, Ops& ops) const {
  const core::Camera& cam = scene_.camera;
  glm::dvec3 vv[3];
  for (int k = 0; k < 3; ++k) vv[k] = to_space[k] * (cam.local_viewer ? cam.position - v[k].position : -cam.forward());
  solve_planes(ps, inv_w, t.vt, vv, ops);
  ops += Ops{/*add*/ 6 + 3, /*mul*/ 9} * 3;
  for (size_t light = 0; light < scene_.lights.size() && light < size_t(kMaxLights); ++light) {
    const core::Light& l = scene_.lights[light];
    glm::dvec3 lv[3];
    for (int k = 0; k < 3; ++k)
      lv[k] = to_space[k] * (l.type == core::Light::Type::Point ? l.position - v[k].position : -l.direction);
    solve_planes(ps, inv_w, t.lt[light], lv, ops);
    ops += Ops{/*add*/ 6 + 3, /*mul*/ 9} * 3;
  }
}

// The paper's unit L and H of every light at the vertices, in the texture's space, as
// planes.
void SetupKernel::setup_unit_bump_vectors(const Vertex v[3], const BumpFrame& f, const glm::dmat3 to_space[3],
                                          const float inv_w[3], const PlaneSolver<float>& ps, TriangleSetup& t,
                                          Ops& ops) const {
  const core::Camera& cam = scene_.camera;
  for (size_t light = 0; light < scene_.lights.size() && light < size_t(kMaxLights); ++light) {
    const core::Light& l = scene_.lights[light];
    glm::dvec3 lv[3], hv[3];
    for (int k = 0; k < 3; ++k) {
      glm::dvec3 L = -l.direction;
      if (l.type == core::Light::Type::Point) {
        const glm::dvec3 d = l.position - v[k].position;
        L = glm::dot(d, d) > 0 ? glm::normalize(d) : f.n[k];
        ops += Ops{/*add*/ 3} + kOpsNormalize3;
      }
      glm::dvec3 V = -cam.forward();
      if (cam.local_viewer) {
        const glm::dvec3 d = cam.position - v[k].position;
        V = glm::dot(d, d) > 0 ? glm::normalize(d) : f.n[k];
        ops += Ops{/*add*/ 3} + kOpsNormalize3;
      }
      const glm::dvec3 h = L + V;
      const glm::dvec3 H = glm::dot(h, h) > 0 ? glm::normalize(h) : f.n[k];
      lv[k] = to_space[k] * L;
      hv[k] = to_space[k] * H;
      ops += Ops{/*add*/ 3 + 12, /*mul*/ 18} + kOpsNormalize3;  // H, two 3×3 products
    }
    solve_planes(ps, inv_w, t.lt[light], lv, ops);
    solve_planes(ps, inv_w, t.ht[light], hv, ops);
  }
}

}  // namespace shadetlm::modules
