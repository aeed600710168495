#pragma once
// A triangle mesh as the shading pipeline sees it: per-vertex position, unit normal,
// unit tangent with handedness (w = ±1, bitangent B = w · N × T) and texture
// coordinates; triangles index the vertices and are counter-clockwise seen from the
// front.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace shadetlm::core {

struct Mesh {
  std::vector<glm::dvec3> positions;
  std::vector<glm::dvec3> normals;
  std::vector<glm::dvec4> tangents;
  std::vector<glm::dvec2> uvs;
  std::vector<glm::u32vec3> triangles;
  bool uvs_given = true;  // false: a file without texture coordinates (its uvs are 0)

  size_t vertex_count() const { return positions.size(); }
  // Adds one vertex and returns its index.
  uint32_t add(glm::dvec3 p, glm::dvec3 n, glm::dvec4 t, glm::dvec2 uv);
};

// Built-in primitives, centred on the origin. `plane` lies in z = 0 facing +z, u along
// +x and v along +y, cut into nx × ny quads; uv spans [0, repeat.x] × [0, repeat.y], so
// that a repeating texture tiles `repeat` times.
Mesh make_plane(glm::dvec2 size, glm::ivec2 tessellation, glm::dvec2 uv_repeat = {1, 1});
// Sphere around the y axis: u runs with longitude, v from the south pole (0) to the
// north pole (1).
Mesh make_sphere(double radius, int segments, int rings);
// Torus around the y axis: u runs around the axis, v around the tube.
Mesh make_torus(double major_radius, double minor_radius, int segments, int sides);
// Cube with flat faces, each face carrying its own uv square [0,1]².
Mesh make_cube(double size);

// A unit tangent orthogonal to n, for vertices that have no uv parameterization.
glm::dvec3 any_tangent(glm::dvec3 n);

}  // namespace shadetlm::core
