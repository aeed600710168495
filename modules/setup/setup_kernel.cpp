#include "modules/setup/setup_kernel.hpp"

#include <algorithm>
#include <cmath>

namespace modules {

SetupKernel::SetupKernel(const core::Scene& scene, bool perspective)
    : scene_(scene),
      perspective_(perspective),
      view_projection_(scene.camera.projection() * scene.camera.view()),
      local_viewer_(scene.camera.local_viewer) {
  for (size_t i = 0; i < scene.lights.size(); ++i)
    if (scene.lights[i].type == core::Light::Type::Point) point_lights_.push_back(int(i));
}

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
  if (t.material->texture >= 0)
    for (int c = 0; c < 2; ++c) perspective_plane(t.uv[c], v[0].uv[c], v[1].uv[c], v[2].uv[c]);
  ops_ += ops;
  return true;
}

}  // namespace modules
