#include "shadetlm/core/mesh.hpp"

#include <cmath>

namespace shadetlm::core {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

uint32_t Mesh::add(glm::dvec3 p, glm::dvec3 n, glm::dvec4 t, glm::dvec2 uv) {
  positions.push_back(p);
  normals.push_back(n);
  tangents.push_back(t);
  uvs.push_back(uv);
  return static_cast<uint32_t>(positions.size() - 1);
}

glm::dvec3 any_tangent(glm::dvec3 n) {
  // Cross with the axis least aligned with n, so the result never degenerates.
  glm::dvec3 a = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  glm::dvec3 t = a - n * glm::dot(a, n);
  return glm::normalize(t);
}

Mesh make_plane(glm::dvec2 size, glm::ivec2 tess, glm::dvec2 uv_repeat) {
  Mesh m;
  for (int j = 0; j <= tess.y; ++j)
    for (int i = 0; i <= tess.x; ++i) {
      glm::dvec2 uv(double(i) / tess.x, double(j) / tess.y);
      m.add({(uv.x - 0.5) * size.x, (uv.y - 0.5) * size.y, 0}, {0, 0, 1}, {1, 0, 0, 1}, uv * uv_repeat);
    }
  const uint32_t row = tess.x + 1;
  for (int j = 0; j < tess.y; ++j)
    for (int i = 0; i < tess.x; ++i) {
      uint32_t a = j * row + i, b = a + 1, c = a + row, d = c + 1;
      m.triangles.push_back({a, b, d});
      m.triangles.push_back({a, d, c});
    }
  return m;
}

Mesh make_sphere(double r, int segments, int rings) {
  Mesh m;
  // Ring 0 is the south pole, ring `rings` the north pole; each ring repeats its first
  // vertex at u = 1 so that the uv seam has its own vertices.
  for (int j = 0; j <= rings; ++j) {
    const double v = double(j) / rings, theta = v * kPi;  // polar angle from -y
    for (int i = 0; i <= segments; ++i) {
      const double u = double(i) / segments, phi = u * 2 * kPi;
      glm::dvec3 n(-std::sin(theta) * std::cos(phi), -std::cos(theta), std::sin(theta) * std::sin(phi));
      // dP/du points along increasing longitude; at the poles the same formula still
      // gives a unit vector tangent to the sphere.
      glm::dvec3 t(std::sin(phi), 0, std::cos(phi));
      m.add(n * r, n, glm::dvec4(t, 1.0), {u, v});
    }
  }
  const uint32_t row = segments + 1;
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < segments; ++i) {
      uint32_t a = j * row + i, b = a + 1, c = a + row, d = c + 1;
      // Seen from outside, u increases to the right and v upwards: (a, b, d, c) is
      // counter-clockwise. The pole rings collapse one triangle of each quad.
      if (j != 0) m.triangles.push_back({a, b, d});          // on ring 0, a = b: the south pole
      if (j != rings - 1) m.triangles.push_back({a, d, c});  // on the last ring, c = d: the north pole
    }
  return m;
}

Mesh make_torus(double R, double r, int segments, int sides) {
  Mesh m;
  for (int j = 0; j <= sides; ++j) {
    const double v = double(j) / sides, psi = v * 2 * kPi;  // around the tube
    for (int i = 0; i <= segments; ++i) {
      const double u = double(i) / segments, phi = u * 2 * kPi;  // around the axis
      glm::dvec3 radial(std::cos(phi), 0, -std::sin(phi));
      glm::dvec3 n = radial * std::cos(psi) + glm::dvec3(0, std::sin(psi), 0);
      glm::dvec3 p = radial * (R + r * std::cos(psi)) + glm::dvec3(0, r * std::sin(psi), 0);
      glm::dvec3 t(-std::sin(phi), 0, -std::cos(phi));  // dP/du, unit
      m.add(p, n, glm::dvec4(t, 1.0), {u, v});
    }
  }
  const uint32_t row = segments + 1;
  for (int j = 0; j < sides; ++j)
    for (int i = 0; i < segments; ++i) {
      uint32_t a = j * row + i, b = a + 1, c = a + row, d = c + 1;
      m.triangles.push_back({a, b, d});
      m.triangles.push_back({a, d, c});
    }
  return m;
}

Mesh make_cube(double size) {
  Mesh m;
  const double h = size / 2;
  // Each face: outward normal n, tangent t (the direction of +u), bitangent b = n × t
  // (the direction of +v).
  const glm::dvec3 faces[6][2] = {{{1, 0, 0}, {0, 0, -1}}, {{-1, 0, 0}, {0, 0, 1}},
                                  {{0, 1, 0}, {1, 0, 0}},  {{0, -1, 0}, {1, 0, 0}},
                                  {{0, 0, 1}, {1, 0, 0}},  {{0, 0, -1}, {-1, 0, 0}}};
  for (const auto& f : faces) {
    const glm::dvec3 n = f[0], t = f[1], b = glm::cross(n, t);
    const uint32_t base = static_cast<uint32_t>(m.vertex_count());
    for (int k = 0; k < 4; ++k) {
      glm::dvec2 uv(k & 1, k >> 1);
      m.add(h * (n + (2 * uv.x - 1) * t + (2 * uv.y - 1) * b), n, glm::dvec4(t, 1.0), uv);
    }
    m.triangles.push_back({base, base + 1, base + 3});
    m.triangles.push_back({base, base + 3, base + 2});
  }
  return m;
}

}  // namespace shadetlm::core
