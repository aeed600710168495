// The scene model's own functions (the core component): names of its enumerations, the
// camera's matrices, objects in world space. Reading a scene file is the io component's
// (scene.cpp).
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "shadetlm/core/bump_map.hpp"
#include "shadetlm/core/scene.hpp"

namespace shadetlm::core {

const char* to_string(ShadingPath p) {
  switch (p) {
    case ShadingPath::Phong: return "phong";
    case ShadingPath::BumpClassic: return "bump-classic";
    case ShadingPath::BumpTangent: return "bump-tangent";
    case ShadingPath::BumpSquare: return "bump-square";
    case ShadingPath::BumpObject: return "bump-object";
    case ShadingPath::TextureScreen: return "texture-screen";
    case ShadingPath::TextureObject: return "texture-object";
    case ShadingPath::Parallax: return "parallax";
  }
  return "?";
}

ShadingPath parse_shading_path(const std::string& name) {
  for (ShadingPath p : {ShadingPath::Phong, ShadingPath::BumpClassic, ShadingPath::BumpTangent, ShadingPath::BumpSquare,
                        ShadingPath::BumpObject, ShadingPath::TextureScreen, ShadingPath::TextureObject,
                        ShadingPath::Parallax})
    if (name == to_string(p)) return p;
  throw std::invalid_argument("unknown shading path " + name);
}

const char* to_string(ParallaxMethod m) {
  switch (m) {
    case ParallaxMethod::Offset: return "offset";
    case ParallaxMethod::Steep: return "steep";
    case ParallaxMethod::Pom: return "pom";
    case ParallaxMethod::Relief: return "relief";
    case ParallaxMethod::Distance: return "distance";
    case ParallaxMethod::Cone: return "cone";
  }
  return "?";
}

const char* to_string(DistanceMap m) {
  switch (m) {
    case DistanceMap::Refined: return "refined";
    case DistanceMap::BoxGap: return "box-gap";
    case DistanceMap::Donnelly: return "donnelly";
  }
  return "?";
}

const char* to_string(ConeKind k) { return k == ConeKind::Relaxed ? "relaxed" : "classic"; }

// ---------------------------------------------------------------- camera

glm::dvec3 Camera::forward() const { return glm::normalize(target - position); }
glm::dvec3 Camera::right() const { return glm::normalize(glm::cross(forward(), up)); }
glm::dvec3 Camera::true_up() const { return glm::cross(right(), forward()); }

glm::dmat4 Camera::view() const { return glm::lookAtRH(position, target, up); }

glm::dmat4 Camera::projection() const {
  return glm::perspectiveRH_NO(glm::radians(fov_y_deg), double(width) / height, near, far);
}

// ---------------------------------------------------------------- world space

Mesh to_world(const Object& object) {
  const glm::dmat3 m3(object.model);
  const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(m3));
  const double handedness = glm::determinant(m3) < 0 ? -1.0 : 1.0;
  Mesh w;
  w.positions.reserve(object.mesh.vertex_count());
  for (size_t i = 0; i < object.mesh.vertex_count(); ++i) {
    glm::dvec3 p = glm::dvec3(object.model * glm::dvec4(object.mesh.positions[i], 1.0));
    glm::dvec3 n = glm::normalize(normal_matrix * object.mesh.normals[i]);
    glm::dvec4 t4 = object.mesh.tangents[i];
    glm::dvec3 t = m3 * glm::dvec3(t4);
    t -= n * glm::dot(n, t);
    t = glm::length(t) > 1e-12 ? glm::normalize(t) : any_tangent(n);
    w.add(p, n, glm::dvec4(t, t4.w * handedness), object.mesh.uvs[i]);
  }
  w.triangles = object.mesh.triangles;
  // A mirroring transform turns counter-clockwise triangles clockwise: restore the
  // winding so that the front stays where the normals point.
  if (handedness < 0)
    for (auto& tri : w.triangles) std::swap(tri.y, tri.z);
  return w;
}

}  // namespace shadetlm::core
