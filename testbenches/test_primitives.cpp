// Built-in primitives: unit normals, tangents orthogonal to normals with the right
// handedness, counter-clockwise fronts, and closed meshes closed.
#include <map>

#include "shadetlm/core/mesh.hpp"
#include "test_util.hpp"

using namespace shadetlm;  // core::, modules::, reference::

namespace {
struct Named {
  const char* name;
  core::Mesh mesh;
  bool closed;
};

std::vector<Named> primitives() {
  return {{"plane", core::make_plane({2, 3}, {4, 5}), false},
          {"sphere", core::make_sphere(1.5, 24, 12), true},
          {"sphere-coarse", core::make_sphere(1, 3, 2), true},
          {"torus", core::make_torus(1, 0.3, 32, 16), true},
          {"cube", core::make_cube(2), true}};
}

// Counts how many triangles use each undirected edge, with vertices welded by
// position (uv seams and cube corners duplicate positions).
std::map<std::pair<int, int>, int> edge_uses(const core::Mesh& m, std::map<std::pair<int, int>, int>* directed) {
  std::map<std::tuple<long, long, long>, int> weld;
  std::vector<int> id(m.vertex_count());
  for (size_t i = 0; i < m.vertex_count(); ++i) {
    auto key = std::make_tuple(std::lround(m.positions[i].x * 1e6), std::lround(m.positions[i].y * 1e6),
                               std::lround(m.positions[i].z * 1e6));
    id[i] = weld.emplace(key, int(weld.size())).first->second;
  }
  std::map<std::pair<int, int>, int> uses;
  for (const auto& t : m.triangles) {
    int v[3] = {id[t.x], id[t.y], id[t.z]};
    for (int k = 0; k < 3; ++k) {
      int a = v[k], b = v[(k + 1) % 3];
      ++uses[{std::min(a, b), std::max(a, b)}];
      ++(*directed)[{a, b}];
    }
  }
  return uses;
}
}  // namespace

TEST_CASE("primitive normals and tangents are unit and orthogonal", "[primitives]") {
  for (const auto& p : primitives()) {
    INFO(p.name);
    const core::Mesh& m = p.mesh;
    REQUIRE(m.normals.size() == m.vertex_count());
    REQUIRE(m.tangents.size() == m.vertex_count());
    REQUIRE(m.uvs.size() == m.vertex_count());
    for (size_t i = 0; i < m.vertex_count(); ++i) {
      CHECK(glm::length(m.normals[i]) == Approx(1.0).margin(1e-12));
      CHECK(glm::length(glm::dvec3(m.tangents[i])) == Approx(1.0).margin(1e-12));
      CHECK(std::abs(glm::dot(m.normals[i], glm::dvec3(m.tangents[i]))) < 1e-12);
      CHECK(std::abs(m.tangents[i].w) == 1.0);
    }
  }
}

TEST_CASE("primitive triangles face where the normals point, tangents along +u", "[primitives]") {
  for (const auto& p : primitives()) {
    INFO(p.name);
    const core::Mesh& m = p.mesh;
    for (const auto& t : m.triangles) {
      const glm::dvec3 a = m.positions[t.x], b = m.positions[t.y], c = m.positions[t.z];
      const glm::dvec3 ng = glm::cross(b - a, c - a);
      REQUIRE(glm::length(ng) > 1e-12);  // no degenerate triangles (poles included)
      const glm::dvec3 n = m.normals[t.x] + m.normals[t.y] + m.normals[t.z];
      CHECK(glm::dot(ng, n) > 0);
      // dP/du of the triangle from its uv: T must point the same way, and
      // B = w · N × T the same way as dP/dv.
      const glm::dvec2 du1 = m.uvs[t.y] - m.uvs[t.x], du2 = m.uvs[t.z] - m.uvs[t.x];
      const double det = du1.x * du2.y - du2.x * du1.y;
      if (std::abs(det) < 1e-12) continue;
      const glm::dvec3 dpdu = ((b - a) * du2.y - (c - a) * du1.y) / det;
      const glm::dvec3 dpdv = ((c - a) * du1.x - (b - a) * du2.x) / det;
      const glm::dvec4 t4 = m.tangents[t.x];
      CHECK(glm::dot(glm::dvec3(t4), dpdu) > 0);
      CHECK(glm::dot(t4.w * glm::cross(m.normals[t.x], glm::dvec3(t4)), dpdv) > 0);
    }
  }
}

TEST_CASE("closed primitives are closed and consistently wound", "[primitives]") {
  for (const auto& p : primitives()) {
    INFO(p.name);
    std::map<std::pair<int, int>, int> directed;
    auto uses = edge_uses(p.mesh, &directed);
    int boundary = 0;
    for (const auto& [edge, n] : uses) {
      if (p.closed) CHECK(n == 2);
      boundary += n == 1;
    }
    // Consistent winding: each directed edge is used once at most.
    for (const auto& [edge, n] : directed) CHECK(n == 1);
    if (!p.closed) CHECK(boundary > 0);
  }
}
