#pragma once
// The scene: camera, lights, materials, textures and objects, read from scene format
// v1 (docs/scene-format.md). Everything downstream — the golden model and the
// pipeline — starts from this one description.
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "shadetlm/core/mesh.hpp"
#include "shadetlm/core/pipeline_config.hpp"
#include "shadetlm/core/texture.hpp"

namespace shadetlm::core {

struct Camera {
  glm::dvec3 position{0, 0, 5}, target{0, 0, 0}, up{0, 1, 0};
  double fov_y_deg = 45;
  int width = 640, height = 480;
  double near = 0.1, far = 100;
  // A local viewer sees each point from the camera position; a viewer at infinity
  // sees every point along the camera's forward axis (V constant over the frame).
  bool local_viewer = true;

  glm::dvec3 forward() const;  // unit, from the position towards the target
  glm::dvec3 right() const;    // unit, to the right of the image
  glm::dvec3 true_up() const;  // unit, towards the top of the image
  glm::dmat4 view() const;     // world → eye (right-handed, looking down −z)
  glm::dmat4 projection() const;  // eye → clip (OpenGL-style, z_ndc in [−1, 1])
};

struct Light {
  enum class Type { Directional, Point };
  Type type = Type::Directional;
  glm::dvec3 direction{0, 0, -1};  // directional: the unit direction the light travels
  glm::dvec3 position{0, 0, 0};    // point
  glm::dvec3 color{1, 1, 1};
  double intensity = 1;
  glm::dvec3 radiance() const { return color * intensity; }
};

// Shading paths a material can select (docs/scene-format.md). The bump paths: the
// classic hardware of the bump-mapping paper's Fig. 2, and the proposed hardware of
// Fig. 3 reading a texture of perturbed normals in tangent space (general form (9) or
// square patch (10)–(11)) or in object space. Parallax and texturing add theirs here.
//
// Texturing paths (object-space texturing paper): the colour texture filtered in the
// screen plane by the texture unit (texture-screen), or splatted from object space by
// texel_project (texture-object). A phong material with a texture reads it bilinearly
// at the finest level.
//
// Parallax (parallax paper): the colour texture read where the view ray meets the
// relief of the height map, found by the parallax block's tracer (docs/parallax.md).
enum class ShadingPath { Phong, BumpClassic, BumpTangent, BumpSquare, BumpObject, TextureScreen, TextureObject, Parallax };
const char* to_string(ShadingPath p);
ShadingPath parse_shading_path(const std::string& name);
// Paths whose normal is fetched from a texture of perturbed normals (Fig. 3), lit in
// the texture's space (tangent or object) rather than in world space.
inline bool fetches_normal(ShadingPath p) {
  return p == ShadingPath::BumpTangent || p == ShadingPath::BumpSquare || p == ShadingPath::BumpObject;
}
inline bool bump_path(ShadingPath p) {
  return p == ShadingPath::BumpClassic || fetches_normal(p);
}

// The parallax block's method and its settings (material "parallax": docs/scene-format.md).
enum class ParallaxMethod { Offset, Steep, Pom, Relief, Distance, Cone };
const char* to_string(ParallaxMethod m);
// The distance method's map (docs/parallax.md): the paper's refined map, the box-gap
// map it refines (safe for nearest reads, with the exact cell finish), or Donnelly's
// Euclidean map traced as published (a fixed count of trilinear sphere steps).
enum class DistanceMap { Refined, BoxGap, Donnelly };
const char* to_string(DistanceMap m);
// The cone method's map (docs/parallax.md): classic cones, free of relief, or relaxed
// ones, safe for rays at or above min_elevation_deg, that a step may end inside.
enum class ConeKind { Classic, Relaxed };
const char* to_string(ConeKind k);
struct ParallaxSettings {
  ParallaxMethod method = ParallaxMethod::Distance;
  DistanceMap map = DistanceMap::Refined;  // distance
  ConeKind cones = ConeKind::Classic;      // cone
  int steps = 16;            // distance on Donnelly's map: the fixed count of sphere steps
  double depth = 0.05;       // the relief's depth in uv units (≤ 0: flat, uv unchanged)
  int slices = 16;           // D: the distance and cone maps' depth in voxels
  int max_iterations = 256;  // the tracer's cap (then it stops where it is)
  bool early_exit = true;    // false: a fixed-length loop, every pixel pays the full count
  int layers_min = 8, layers_max = 32;  // steep, pom, relief: layers facing / grazing
  int binary_steps = 6;      // relief
  double min_elevation_deg = 10;  // refined map, relaxed cones: admissible directions (tracer space)
  double margin = 0;              // refined map: voxels taken off (safety)
  // A map written by `shadetlm precompute` (distance, refined or cone) read instead of
  // building one; checked against these settings and the height map. Empty: built.
  std::string map_file;
};

struct Material {
  std::string name;
  glm::dvec3 ambient{0.1, 0.1, 0.1}, diffuse{0.8, 0.8, 0.8}, specular{0.2, 0.2, 0.2};
  double shininess = 32;
  int texture = -1;       // colour texture modulating ambient and diffuse; -1 none
  int height_map = -1;    // height map (first channel); -1 none
  double height_scale = 0;  // F = height_scale · h, in world units per unit of h
  int normal_map = -1;    // precomputed perturbed normals (shadetlm precompute); -1 none
  double square_k = 1;    // bump-square: |Pu| = |Pv| = k assumed (relative bump height)
  ShadingPath path = ShadingPath::Phong;
  ParallaxSettings parallax;  // path parallax
};

struct Object {
  std::string name;
  Mesh mesh;              // in object space
  glm::dmat4 model{1.0};  // object → world
  int material = 0;
  bool cull_back = false;  // drop triangles facing away from the camera
};

struct Scene {
  std::string file;  // where it was read from ("<built-in demo>" for the demo)
  std::vector<std::string> inputs;  // the files it read: itself, images, meshes
  nlohmann::json source;  // the scene JSON after --set overrides
  Camera camera;
  glm::dvec3 ambient{0, 0, 0};
  glm::dvec3 background{0, 0, 0};
  std::vector<Light> lights;
  std::vector<Texture> textures;  // colour textures are stored decoded to linear
  std::vector<Material> materials;
  std::vector<Object> objects;
  PipelineConfig pipeline;
};

// An object's mesh in world space: positions by the model matrix, normals by its
// inverse transpose, tangents by the model matrix; normals and tangents renormalized
// per vertex (and the tangent made orthogonal to the normal). This is the scene's
// definition of its vertices, shared by the golden model and the pipeline.
Mesh to_world(const Object& object);

// ---- The io component (shadetlm::io, linked apart: file formats) from here on.
// Loads a scene file; `overrides` are "key=value" strings applied to the JSON first
// (dotted keys, numeric array indices: "lights.0.intensity=2"). Throws InputError.
Scene load_scene(const std::string& file, const std::vector<std::string>& overrides = {});
// Reads a scene from JSON text; relative paths resolve against `base_dir`.
Scene load_scene_text(const std::string& text, const std::string& name,
                      const std::string& base_dir,
                      const std::vector<std::string>& overrides = {});
// The built-in demo scene (scenes/demo.json, compiled in).
Scene load_demo_scene(const std::vector<std::string>& overrides = {});
const std::string& demo_scene_text();

// Applies one "key=value" override to a JSON document. The value is read as JSON
// when it parses as JSON, else as a string.
void apply_override(nlohmann::json& doc, const std::string& assignment,
                    const std::string& file);

}  // namespace shadetlm::core
