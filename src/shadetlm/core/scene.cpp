#include "shadetlm/core/scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include "shadetlm/core/bump_map.hpp"
#include "shadetlm/core/input_file.hpp"
#include "shadetlm/core/memory_budget.hpp"
#include "shadetlm/core/json_reader.hpp"
#include "shadetlm/core/mesh_io.hpp"

namespace shadetlm::core {

namespace fs = std::filesystem;

// ---------------------------------------------------------------- overrides

void apply_override(json& doc, const std::string& assignment, const std::string& file) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError(file, assignment, "expected key=value");
  const std::string key = assignment.substr(0, eq), text = assignment.substr(eq + 1);
  // Not JSON: a bare string such as `exact`. Tested with accept(), not by catching the
  // parse error: overrides are read after a SystemC simulation too (the golden tests'
  // further configurations), where AddressSanitizer misreads a throw on QuickThreads.
  json value = text;
  if (json::accept(text)) {
    try {
      value = json::parse(text);
    } catch (const json::exception& e) {  // JSON, but not representable (1e999)
      throw InputError(file, key, std::string("cannot read the value: ") + e.what());
    }
  }
  json* node = &doc;
  std::string walked;
  size_t start = 0;
  while (true) {
    const size_t dot = key.find('.', start);
    const std::string part = key.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    if (part.empty()) throw InputError(file, key, "empty component in the key");
    walked += (walked.empty() ? "" : ".") + part;
    json* next = nullptr;
    if (node->is_array()) {
      char* end = nullptr;
      unsigned long index = std::strtoul(part.c_str(), &end, 10);
      if (*end != '\0' || index >= node->size())
        throw InputError(file, walked,
                         "no such element (the array has " + std::to_string(node->size()) + ")");
      next = &(*node)[index];
    } else {
      if (node->is_null()) *node = json::object();
      if (!node->is_object())
        throw InputError(file, walked, "cannot set a member of a value that is not an object");
      next = &(*node)[part];
    }
    if (dot == std::string::npos) {
      *next = value;
      return;
    }
    node = next;
    start = dot + 1;
  }
}

// ---------------------------------------------------------------- loading

namespace {

// Lengths the model accepts: far enough from double's limits that products of
// positions, and determinants of scales, neither overflow nor underflow.
constexpr double kMaxLength = 1e6, kMinLength = 1e-6;

glm::dvec3 position(JsonReader& r, const std::string& key, std::optional<glm::dvec3> fallback) {
  glm::dvec3 p = r.vec3(key, fallback);
  for (int k = 0; k < 3; ++k)
    if (std::abs(p[k]) > kMaxLength) r.fail(key, "coordinates must lie within ±1e6");
  return p;
}

glm::dmat4 read_transform(JsonReader r) {
  glm::dvec3 translate = position(r, "translate", glm::dvec3(0));
  glm::dvec3 rotate = r.vec3("rotate", glm::dvec3(0));
  glm::dvec3 scale(1);
  if (r.has("scale") && r.raw("scale").is_number())
    scale = glm::dvec3(r.number("scale"));
  else
    scale = r.vec3("scale", glm::dvec3(1));
  for (int k = 0; k < 3; ++k)
    if (!(std::abs(scale[k]) >= kMinLength && std::abs(scale[k]) <= kMaxLength))
      r.fail("scale", "each scale factor's size must lie in [1e-6, 1e6] (a scale of 0 flattens the object)");
  r.finish();
  // M = T · Rz · Ry · Rx · S: scale first, then rotate about x, y, z, then translate.
  glm::dmat4 m = glm::translate(glm::dmat4(1), translate);
  m = glm::rotate(m, glm::radians(rotate.z), glm::dvec3(0, 0, 1));
  m = glm::rotate(m, glm::radians(rotate.y), glm::dvec3(0, 1, 0));
  m = glm::rotate(m, glm::radians(rotate.x), glm::dvec3(1, 0, 0));
  return glm::scale(m, scale);
}

// Colours lie in [0, 1e4] and light intensities in [0, 1e6] (docs/scene-format.md): the
// largest product a pixel forms — intensity, light colour, material colour, texel, over
// a point light's squared distance down to 1e-6 — stays near 1e30, far inside float32
// (3.4e38), so that no input can put an infinity into a frame.
constexpr double kMaxColour = 1e4, kMaxIntensity = 1e6;

glm::dvec3 color(JsonReader& r, const std::string& key, glm::dvec3 fallback) {
  glm::dvec3 c = r.vec3(key, fallback);
  if (c.x < 0 || c.y < 0 || c.z < 0) r.fail(key, "colours cannot be negative");
  if (c.x > kMaxColour || c.y > kMaxColour || c.z > kMaxColour)
    r.fail(key, "colour components may not exceed 1e4 (their products must stay finite in float32)");
  return c;
}

std::string resolve(const std::string& base_dir, const std::string& path) {
  fs::path p(path);
  return p.is_absolute() ? path : (fs::path(base_dir) / p).lexically_normal().string();
}

Texture read_texture(JsonReader r, const std::string& name, const std::string& base_dir) {
  const std::string type = r.choice(
      "type", std::nullopt,
      {"image", "checker", "bricks", "tiles", "value-noise", "gradient-noise", "ridges", "steps"});
  Texture t;
  if (type == "image") {
    const std::string file = resolve(base_dir, r.string("file"));
    try {
      t = load_texture_file(file);
    } catch (const InputError& e) {
      r.fail("file", e.what());
    }
    if (r.has("colorspace")) t.srgb = r.choice("colorspace", std::nullopt, {"srgb", "linear"}) == "srgb";
  } else {
    ProceduralParams p;
    p.size = r.ivec2("size", glm::ivec2(256, 256), 1, 8192);
    const std::string why = MemoryBudget::process().claim(uint64_t(p.size.x) * uint64_t(p.size.y) * 16);
    if (!why.empty()) r.fail("size", why);
    if (r.has("cells") && r.raw("cells").is_number_integer())
      p.cells = glm::ivec2(r.integer("cells", std::nullopt, 1, 4096));
    else
      p.cells = r.ivec2("cells", glm::ivec2(8, 8), 1, 4096);
    p.octaves = r.integer("octaves", 1, 1, 12);
    p.levels = r.integer("levels", 4, 1, 1024);
    p.gap = r.number("gap", 0.05, 0, 0.5);
    p.seed = static_cast<uint32_t>(r.integer("seed", 1, 0, 2147483647));
    if (r.has("colors")) {
      auto colors = r.vec3_list("colors", 2);
      for (size_t k = 0; k < colors.size(); ++k)
        if (!(glm::all(glm::greaterThanEqual(colors[k], glm::dvec3(0))) &&
              glm::all(glm::lessThanEqual(colors[k], glm::dvec3(kMaxColour)))))
          r.fail("colors." + std::to_string(k), "colour components lie in [0, 1e4] (products must stay finite in float32)");
      p.color_a = colors[0];
      p.color_b = colors[1];
    }
    if (type == "checker") t = make_checker(p);
    else if (type == "bricks") t = make_bricks(p);
    else if (type == "tiles") t = make_tiles(p);
    else if (type == "value-noise") t = make_value_noise(p);
    else if (type == "gradient-noise") t = make_gradient_noise(p);
    else if (type == "ridges") t = make_ridges(p);
    else t = make_steps(p);
  }
  t.name = name;
  t.wrap = r.choice("wrap", std::string("repeat"), {"repeat", "clamp"}) == "repeat" ? Wrap::Repeat : Wrap::Clamp;
  r.finish();
  return t;
}

// A tessellated primitive's memory (a grid of m × n quads), counted before it is built.
void take_mesh_memory(JsonReader& r, const std::string& field, int m, int n) {
  const uint64_t vertices = uint64_t(m + 1) * uint64_t(n + 1), triangles = 2 * uint64_t(m) * uint64_t(n);
  const std::string why = MemoryBudget::process().claim(mesh_bytes(vertices, triangles));
  if (!why.empty()) r.fail(field, why);
}

Mesh read_shape(JsonReader& r, const std::string& shape, const std::string& base_dir) {
  if (shape == "plane") {
    const glm::dvec2 size = r.vec2("size", glm::dvec2(2, 2));
    for (int k = 0; k < 2; ++k)
      if (!(size[k] >= kMinLength && size[k] <= kMaxLength)) r.fail("size", "must lie in [1e-6, 1e6]");
    const glm::dvec2 repeat = r.vec2("uv_repeat", glm::dvec2(1, 1));
    if (!(repeat.x > 0 && repeat.y > 0 && repeat.x <= 1e4 && repeat.y <= 1e4))
      r.fail("uv_repeat", "must lie in (0, 1e4]");
    const glm::ivec2 tessellation = r.ivec2("tessellation", glm::ivec2(1, 1), 1, 2048);
    take_mesh_memory(r, "tessellation", tessellation.x, tessellation.y);
    return make_plane(size, tessellation, repeat);
  }
  if (shape == "sphere") {
    const double radius = r.number("radius", 1.0, kMinLength, kMaxLength);
    const int segments = r.integer("segments", 48, 3, 2048), rings = r.integer("rings", 24, 2, 2048);
    take_mesh_memory(r, "segments", segments, rings);
    return make_sphere(radius, segments, rings);
  }
  if (shape == "torus") {
    double major = r.number("major_radius", 1.0, kMinLength, kMaxLength);
    double minor = r.number("minor_radius", 0.35, kMinLength, kMaxLength);
    if (minor >= major) r.fail("minor_radius", "must be smaller than major_radius");
    const int segments = r.integer("segments", 48, 3, 2048), sides = r.integer("sides", 24, 3, 2048);
    take_mesh_memory(r, "segments", segments, sides);
    return make_torus(major, minor, segments, sides);
  }
  if (shape == "cube") return make_cube(r.number("size", 1.0, kMinLength, kMaxLength));
  const std::string file = resolve(base_dir, r.string("file"));
  Mesh mesh;
  try {
    mesh = load_mesh_file(file);
  } catch (const InputError& e) {
    r.fail("file", e.what());
  }
  const std::string why = MemoryBudget::process().claim(mesh_bytes(mesh.vertex_count(), mesh.triangles.size()));
  if (!why.empty()) r.fail("file", file + ": " + why);
  return mesh;
}

void check_camera(JsonReader& r, const Camera& c) {
  const glm::dvec3 f = c.target - c.position;
  if (glm::length(f) < 1e-12) r.fail("target", "the camera's target equals its position");
  if (glm::length(c.up) < 1e-12) r.fail("up", "the up vector is zero");
  if (glm::length(glm::cross(glm::normalize(f), glm::normalize(c.up))) < 1e-9)
    r.fail("up", "the up vector is parallel to the viewing direction");
  if (c.far <= c.near) r.fail("far", "must be greater than near");
}

// A material's path and its inputs: a texturing path needs a texture with power-of-two
// sides; a bump path needs a height map (or, except the classic path, a precomputed
// normal map), usable by the texture unit.
void check_material_path(JsonReader& r, const Material& m, const std::vector<Texture>& textures) {
  if ((m.path == ShadingPath::TextureScreen || m.path == ShadingPath::TextureObject) && m.texture < 0)
    r.fail("path", std::string(to_string(m.path)) + " needs a texture in material \"" + m.name + "\"");
  if ((m.path == ShadingPath::TextureScreen || m.path == ShadingPath::TextureObject) && m.height_map >= 0)
    r.fail("height_map", std::string(to_string(m.path)) + " does not bump-map (one path per material)");
  if (m.path == ShadingPath::TextureScreen || m.path == ShadingPath::TextureObject) {
    // Mip levels halve exactly only for power-of-two sides (the texture unit addresses
    // them by shifts).
    const Texture& t = textures[size_t(m.texture)];
    auto power_of_two = [](int n) { return n > 0 && (n & (n - 1)) == 0; };
    if (!power_of_two(t.width) || !power_of_two(t.height))
      r.fail("texture", "texture \"" + t.name + "\" is " + std::to_string(t.width) + "×" + std::to_string(t.height) + ": " +
                            to_string(m.path) + " needs power-of-two sides (mip levels); resample the image");
  }
  if (m.path == ShadingPath::Parallax && m.height_map < 0)
    r.fail("path", "parallax needs a height_map in material \"" + m.name + "\"");
  if (m.path == ShadingPath::Parallax && m.height_map >= 0 && textures[size_t(m.height_map)].wrap == Wrap::Clamp)
    r.fail("height_map", "the parallax maps tile: the height map must wrap (\"wrap\": \"repeat\")");
  if (m.path == ShadingPath::Parallax && r.has("height_scale"))
    r.fail("height_scale", "the parallax path takes its depth from parallax.depth (uv units)");
  const bool bump = bump_path(m.path);
  if (!bump && m.normal_map >= 0) r.fail("normal_map", "given, but the path is phong (use a bump-* path)");
  if (m.path == ShadingPath::BumpClassic && m.normal_map >= 0)
    r.fail("normal_map", "the bump-classic path reads the height map, not a normal map");
  if (bump && m.height_map < 0 && m.normal_map < 0)
    r.fail("path", std::string(to_string(m.path)) + " needs a height_map" +
                       (m.path == ShadingPath::BumpClassic ? "" : " or a normal_map") + " in material \"" +
                       m.name + "\"");
  if (r.has("square_k") && m.path != ShadingPath::BumpSquare) r.fail("square_k", "only the bump-square path uses it");
  if (r.has("square_k") && m.normal_map >= 0)
    r.fail("square_k", "a precomputed normal_map has its k built in (shadetlm precompute normalmap --k)");
  auto usable = [&](int index, const char* key) {
    if ((!bump && m.path != ShadingPath::Parallax) || index < 0) return;
    try {
      check_height_map(textures[size_t(index)], textures[size_t(index)].name, "");
    } catch (const InputError& e) {
      r.fail(key, e.what());
    }
  };
  usable(m.height_map, "height_map");
  usable(m.normal_map, "normal_map");
}

// The camera object: where it stands and looks, its field of view, resolution and
// depth range.
Camera read_camera(JsonReader r) {
  Camera c;
  c.position = position(r, "position", std::nullopt);
  c.target = position(r, "target", std::nullopt);
  c.up = r.vec3("up", glm::dvec3(0, 1, 0));
  c.fov_y_deg = r.number("fov_y", 45.0, 1e-3, 179.0);
  // Sides up to 16384 (the stress scenes' longest spans); at most 8192² pixels in all,
  // which keeps the golden model's double-precision image within a few GB.
  glm::ivec2 res = r.ivec2("resolution", std::nullopt, 1, 16384);
  if (int64_t(res.x) * int64_t(res.y) > int64_t(8192) * 8192)
    r.fail("resolution", "at most 8192 × 8192 pixels in all, got " + std::to_string(res.x) + " × " + std::to_string(res.y));
  c.width = res.x;
  c.height = res.y;
  c.near = r.number("near", 0.1, 1e-9, 1e12);
  c.far = r.number("far", 1000.0, 1e-9, 1e12);
  c.local_viewer = r.boolean("local_viewer", true);
  check_camera(r, c);
  r.finish();
  return c;
}

// One element of the lights array: a directional or a point light.
Light read_light(JsonReader r) {
  Light l;
  l.type = r.choice("type", std::nullopt, {"directional", "point"}) == "point" ? Light::Type::Point
                                                                            : Light::Type::Directional;
  if (l.type == Light::Type::Directional) {
    glm::dvec3 d = r.vec3("direction");
    // Scaled by its largest component first: 1e200 on each axis is a direction too, whose
    // length overflows.
    const double largest = std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)});
    if (!(largest > 0) || glm::length(d / largest) * largest < 1e-12) r.fail("direction", "the direction is zero");
    l.direction = glm::normalize(d / largest);
  } else {
    l.position = position(r, "position", std::nullopt);
  }
  l.color = color(r, "color", glm::dvec3(1));
  l.intensity = r.number("intensity", 1.0, 0, kMaxIntensity);
  r.finish();
  return l;
}

// The textures object (if any), appended to `textures`; returns each one's index by name.
std::map<std::string, int> read_textures(JsonReader& root, json& doc, const std::string& base_dir,
                                         std::vector<Texture>& textures) {
  std::map<std::string, int> texture_index;
  if (root.has("textures")) {
    JsonReader r = root.object("textures");
    for (auto it = doc["textures"].begin(); it != doc["textures"].end(); ++it) {
      texture_index[it.key()] = static_cast<int>(textures.size());
      textures.push_back(read_texture(r.object(it.key()), it.key(), base_dir));
    }
    r.finish();
  }
  return texture_index;
}

// Materials' references to textures by name, resolved to indices in the scene's textures.
struct TextureRefs {
  const std::map<std::string, int>& texture_index;  // the textures object's, by name
  std::vector<Texture>& textures;                    // the scene's, grown by decoded copies
  std::map<int, int> decoded;  // sRGB texture → its linear copy, made once
  std::map<int, int> normals;  // 8- or 16-bit normal map → its decoded copy (2x − 1), made once
  std::map<std::pair<int, std::string>, int> remapped;  // (normal map, channels) → its copy in the model's axes

  // The normal map that `key` names (-1 if absent): an EXR as stored (N), an 8- or
  // 16-bit image decoded from (N + 1) / 2, whatever its colorspace says.
  // Read through the material's `channels` (normal_map_channels) when they are not R, G,
  // B as x, y, z: a copy per map and reading, made once.
  int read_normal_map(JsonReader& r, const std::string& key, const NormalChannels& channels) {
    int i = read(r, key, false);
    if (i >= 0 && textures[size_t(i)].unorm) {
      auto [d, fresh] = normals.emplace(i, static_cast<int>(textures.size()));
      if (fresh) textures.push_back(decode_unorm_normals(textures[size_t(i)]));
      i = d->second;
    }
    if (i < 0 || channels.identity()) return i;
    auto [d, fresh] = remapped.emplace(std::pair(i, channels.text()), static_cast<int>(textures.size()));
    if (fresh) textures.push_back(remap_normal_channels(textures[size_t(i)], channels));
    return d->second;
  }

  // The texture that `key` names (-1 if absent); a colour texture stored sRGB gives its
  // linear copy.
  int read(JsonReader& r, const std::string& key, bool colour) {
    if (!r.has(key)) return -1;
    std::string tn = r.string(key);
    auto it = texture_index.find(tn);
    if (it == texture_index.end()) r.fail(key, "no texture named \"" + tn + "\" in textures");
    if (colour && textures[it->second].srgb) {
      // A colour texture is used decoded to linear; a height map reads stored values.
      auto [d, fresh] = decoded.emplace(it->second, static_cast<int>(textures.size()));
      if (fresh) textures.push_back(decode_srgb(textures[it->second]));
      return d->second;
    }
    return it->second;
  }
};

// A material's parallax object: the tracing method and its settings, over the defaults in `ps`.
void read_parallax(JsonReader pr, ParallaxSettings& ps) {
  const std::string method =
      pr.choice("method", std::string("distance"), {"offset", "steep", "pom", "relief", "distance", "cone"});
  for (ParallaxMethod pm : {ParallaxMethod::Offset, ParallaxMethod::Steep, ParallaxMethod::Pom,
                            ParallaxMethod::Relief, ParallaxMethod::Distance, ParallaxMethod::Cone})
    if (method == to_string(pm)) ps.method = pm;
  const std::string map = pr.choice("map", std::string(to_string(ps.map)), {"refined", "box-gap", "donnelly"});
  for (DistanceMap dm : {DistanceMap::Refined, DistanceMap::BoxGap, DistanceMap::Donnelly})
    if (map == to_string(dm)) ps.map = dm;
  if (pr.has("map") && ps.method != ParallaxMethod::Distance) pr.fail("map", "only the distance method reads it");
  const std::string cones = pr.choice("cones", std::string(to_string(ps.cones)), {"classic", "relaxed"});
  ps.cones = cones == "relaxed" ? ConeKind::Relaxed : ConeKind::Classic;
  if (pr.has("cones") && ps.method != ParallaxMethod::Cone) pr.fail("cones", "only the cone method reads it");
  ps.steps = pr.integer("steps", ps.steps, 1, 4096);
  if (pr.has("steps") && !(ps.method == ParallaxMethod::Distance && ps.map == DistanceMap::Donnelly))
    pr.fail("steps", "only the distance method on Donnelly's map reads it");
  // Any depth is accepted: 0 or below is documented as flat (uv unchanged).
  ps.depth = pr.number("depth", ps.depth, -1e6, 1e6);
  ps.slices = pr.integer("slices", ps.slices, 1, 256);
  ps.max_iterations = pr.integer("max_iterations", ps.max_iterations, 1, 1 << 16);
  ps.early_exit = pr.boolean("early_exit", ps.early_exit);
  ps.layers_min = pr.integer("layers_min", ps.layers_min, 1, 4096);
  ps.layers_max = pr.integer("layers_max", ps.layers_max, ps.layers_min, 4096);
  ps.binary_steps = pr.integer("binary_steps", ps.binary_steps, 0, 64);
  ps.min_elevation_deg = pr.number("min_elevation_deg", ps.min_elevation_deg, 0.1, 89);
  ps.margin = pr.number("margin", ps.margin, 0, 64);
  if (pr.has("map_file")) {
    if (ps.method != ParallaxMethod::Distance && ps.method != ParallaxMethod::Cone)
      pr.fail("map_file", "only the distance and cone methods read a map");
    ps.map_file = pr.string("map_file");
    if (ps.map_file.empty()) pr.fail("map_file", "an empty path");
  }
  pr.finish();
}

// A material's normal_map_channels: for each stored channel R, G, B, the model's axis it
// holds, with an optional sign ("x", "-y", "z"); each axis once.
NormalChannels read_normal_channels(JsonReader& r, const std::string& key) {
  NormalChannels c;
  if (!r.has(key)) return c;
  const auto items = r.array(key);
  if (items.size() != 3)
    r.fail(key, "expected three axes, the ones R, G and B hold, e.g. [\"x\", \"-y\", \"z\"] (green down)");
  bool seen[3] = {false, false, false};
  for (int k = 0; k < 3; ++k) {
    const auto& [value, field] = items[size_t(k)];
    std::string axis = value->is_string() ? value->get<std::string>() : "";
    c.sign[k] = !axis.empty() && axis[0] == '-' ? -1.0f : 1.0f;
    if (!axis.empty() && (axis[0] == '-' || axis[0] == '+')) axis.erase(0, 1);
    if (axis != "x" && axis != "y" && axis != "z")
      throw InputError(r.file(), field, "expected x, y or z, with a sign if it is read negated (\"-y\")");
    c.axis[k] = axis[0] - 'x';
    if (seen[c.axis[k]]) throw InputError(r.file(), field, "the axis " + axis + " is held by two channels");
    seen[c.axis[k]] = true;
  }
  return c;
}

// One member of the materials object: colours, textures, path and its settings, checked
// against the path.
Material read_material(JsonReader r, const std::string& name, TextureRefs& texture_refs) {
  Material m;
  m.name = name;
  m.ambient = color(r, "ambient", m.ambient);
  m.diffuse = color(r, "diffuse", m.diffuse);
  m.specular = color(r, "specular", m.specular);
  m.shininess = r.number("shininess", m.shininess, 0, 1e6);
  m.texture = texture_refs.read(r, "texture", true);
  m.height_map = texture_refs.read(r, "height_map", false);
  m.height_scale = r.number("height_scale", 0.0, 0, 1e6);
  if (r.has("height_scale") && m.height_map < 0)
    r.fail("height_scale", "given without a height_map");
  const NormalChannels channels = read_normal_channels(r, "normal_map_channels");
  if (r.has("normal_map_channels") && !r.has("normal_map")) r.fail("normal_map_channels", "given without a normal_map");
  m.normal_map = texture_refs.read_normal_map(r, "normal_map", channels);
  m.square_k = r.number("square_k", 1.0, kMinLength, kMaxLength);
  m.path = parse_shading_path(r.choice("path", std::string("phong"),
                                       {"phong", "bump-classic", "bump-tangent", "bump-square", "bump-object",
                                        "texture-screen", "texture-object", "parallax"}));
  if (r.has("parallax")) {
    if (m.path != ShadingPath::Parallax) r.fail("parallax", "given, but the path is not parallax");
    read_parallax(r.object("parallax"), m.parallax);
  }
  check_material_path(r, m, texture_refs.textures);
  r.finish();
  return m;
}

// The materials object (if any), appended to the scene's materials (textures decoded to
// linear are appended to its textures); returns each material's index by name.
std::map<std::string, int> read_materials(JsonReader& root, json& doc,
                                          const std::map<std::string, int>& texture_index, Scene& s) {
  std::map<std::string, int> material_index;
  TextureRefs texture_refs{texture_index, s.textures, {}, {}};
  if (root.has("materials")) {
    JsonReader all = root.object("materials");
    for (auto it = doc["materials"].begin(); it != doc["materials"].end(); ++it) {
      Material m = read_material(all.object(it.key()), it.key(), texture_refs);
      material_index[m.name] = static_cast<int>(s.materials.size());
      s.materials.push_back(m);
    }
    all.finish();
  }
  return material_index;
}

// An object's material: the one it names, or the built-in grey "default" (added to
// `materials` the first time an object needs it).
int read_material_ref(JsonReader& r, std::map<std::string, int>& material_index, std::vector<Material>& materials) {
  if (r.has("material")) {
    std::string mn = r.string("material");
    auto it = material_index.find(mn);
    if (it == material_index.end()) r.fail("material", "no material named \"" + printable(mn) + "\" in materials");
    return it->second;
  }
  if (!material_index.count("default")) {  // the built-in grey
    material_index["default"] = static_cast<int>(materials.size());
    Material m;
    m.name = "default";
    materials.push_back(m);
  }
  return material_index["default"];
}

// Rejects a model matrix other than a rotation times a uniform scale (bump-object).
void check_bump_object_transform(JsonReader& r, const glm::dmat4& model) {
  // Object-space normals and object-space L, H keep their angles only under a
  // rotation and a uniform scale (docs/bump-mapping.md).
  const glm::dmat3 m(model);
  const glm::dmat3 g = glm::transpose(m) * m;
  const double scale = (g[0][0] + g[1][1] + g[2][2]) / 3;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (std::abs(g[i][j] - (i == j ? scale : 0.0)) > 1e-9 * scale)
        r.fail("transform", "bump-object needs a rotation and a uniform scale (object-space normals keep "
                            "their angles to L and H only then); use bump-tangent");
}

// One element of the objects array: shape, name, material, transform and culling.
// A missing material adds the built-in grey to the scene's materials.
Object read_object(JsonReader r, std::map<std::string, int>& material_index, const std::string& base_dir,
                   Scene& s) {
  Object o;
  const std::string shape = r.choice("shape", std::nullopt, {"plane", "sphere", "torus", "cube", "mesh"});
  o.name = r.string("name", shape + std::to_string(s.objects.size()));
  o.mesh = read_shape(r, shape, base_dir);
  o.material = read_material_ref(r, material_index, s.materials);
  if (r.has("transform")) o.model = read_transform(r.object("transform"));
  o.cull_back = r.choice("cull", std::string("none"), {"none", "back"}) == "back";
  const Material& m = s.materials[size_t(o.material)];
  if (m.path == ShadingPath::BumpObject) check_bump_object_transform(r, o.model);
  // Every path but untextured Phong reads the surface's texture coordinates.
  if (!o.mesh.uvs_given && (m.path != ShadingPath::Phong || m.texture >= 0))
    r.fail("file", "the mesh has no texture coordinates, which material \"" + m.name + "\" (" +
                       std::string(to_string(m.path)) + (m.texture >= 0 ? ", textured" : "") + ") reads");
  r.finish();
  return o;
}

// The files a scene reads: itself, its image textures and its mesh files.
std::vector<std::string> files_read(const Scene& s, const json& doc, const std::string& base_dir) {
  std::vector<std::string> files;
  if (s.file != "<built-in demo>") files.push_back(s.file);
  if (doc.contains("textures"))
    for (const auto& [name, t] : doc["textures"].items())
      if (t.is_object() && t.contains("file") && t["file"].is_string()) files.push_back(resolve(base_dir, t["file"]));
  for (const auto& o : doc["objects"])
    if (o.is_object() && o.contains("file") && o["file"].is_string()) files.push_back(resolve(base_dir, o["file"]));
  for (const Material& m : s.materials)
    if (!m.parallax.map_file.empty()) files.push_back(m.parallax.map_file);
  return files;
}

// The pipeline object's settings (the defaults without one).
PipelineConfig read_pipeline(JsonReader& root, const std::string& name) {
  json pipeline = root.has("pipeline") ? root.raw("pipeline") : json();
  return PipelineConfig::from_json(pipeline, name);
}

}  // namespace

Scene load_scene_text(const std::string& text, const std::string& name, const std::string& base_dir,
                      const std::vector<std::string>& overrides) {
  json doc = parse_json_text(text, name);
  for (const auto& o : overrides) apply_override(doc, o, "--set " + o);

  Scene s;
  s.file = name;
  s.source = doc;
  JsonReader root(doc, name, "");
  if (root.integer("format", 1, 1, 1) != 1) root.fail("format", "unsupported");

  s.camera = read_camera(root.object("camera"));

  s.ambient = color(root, "ambient", glm::dvec3(0));
  s.background = color(root, "background", glm::dvec3(0));

  if (root.has("lights"))
    for (const auto& [value, path] : root.array("lights"))
      s.lights.push_back(read_light(JsonReader(*value, name, path)));

  const std::map<std::string, int> texture_index = read_textures(root, doc, base_dir, s.textures);
  std::map<std::string, int> material_index = read_materials(root, doc, texture_index, s);
  for (Material& m : s.materials)
    if (!m.parallax.map_file.empty()) m.parallax.map_file = resolve(base_dir, m.parallax.map_file);

  const auto objects = root.array("objects");
  if (objects.empty()) root.fail("objects", "an empty array: a scene draws at least one object");
  for (const auto& [value, path] : objects)
    s.objects.push_back(read_object(JsonReader(*value, name, path), material_index, base_dir, s));

  s.pipeline = read_pipeline(root, name);
  root.finish();
  s.inputs = files_read(s, doc, base_dir);
  return s;
}

Scene load_scene(const std::string& file, const std::vector<std::string>& overrides) {
  check_input_file(file, "", kMaxSceneBytes);
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file, "", "cannot open the scene file");
  std::stringstream ss;
  ss << in.rdbuf();
  std::string dir = fs::path(file).parent_path().string();
  return load_scene_text(ss.str(), file, dir.empty() ? "." : dir, overrides);
}

Scene load_demo_scene(const std::vector<std::string>& overrides) {
  return load_scene_text(demo_scene_text(), "<built-in demo>", ".", overrides);
}

}  // namespace shadetlm::core
