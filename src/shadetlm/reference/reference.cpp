#include "shadetlm/reference/reference.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "shadetlm/core/coverage.hpp"
#include "shadetlm/core/parallel.hpp"
#include "shadetlm/reference/parallax.hpp"

namespace shadetlm::reference {

glm::dvec3 shade(const core::Scene& scene, const core::Material& m, const glm::dvec3& P,
                 const glm::dvec3& N, const glm::dvec3& tex) {
  const core::Camera& cam = scene.camera;
  const glm::dvec3 V = cam.local_viewer ? glm::normalize(cam.position - P) : -cam.forward();
  glm::dvec3 c = scene.ambient * m.ambient * tex;
  for (const core::Light& light : scene.lights) {
    glm::dvec3 L;
    if (light.type == core::Light::Type::Directional) {
      L = -light.direction;
    } else {
      const glm::dvec3 d = light.position - P;
      if (glm::length(d) == 0) continue;  // a light on the surface lights no direction
      L = glm::normalize(d);
    }
    const double n_dot_l = glm::dot(N, L);
    if (n_dot_l <= 0) continue;  // the light is behind the surface: no diffuse, no highlight
    double highlight = 0;
    const glm::dvec3 h = L + V;
    if (glm::length(h) > 0) {
      const double n_dot_h = glm::dot(N, glm::normalize(h));
      if (n_dot_h > 0) highlight = std::pow(n_dot_h, m.shininess);
    }
    c += light.radiance() * (m.diffuse * tex * n_dot_l + m.specular * highlight);
  }
  return c;
}

namespace {

// A hash of three integers to [0, 1): the jitter of the footprint's strata.
double jitter(uint32_t a, uint32_t b, uint32_t c) {
  uint32_t x = a * 0x9E3779B1u ^ (b + 0x7F4A7C15u) * 0x85EBCA77u ^ (c + 0x165667B1u) * 0xC2B2AE3Du;
  x ^= x >> 16, x *= 0x7feb352du, x ^= x >> 15, x *= 0x846ca68bu, x ^= x >> 16;
  return (x >> 8) * (1.0 / 16777216.0);
}

// The colour texture averaged over the pixel's footprint: 16 × 16 strata of the pixel,
// one jittered sample in each; each sample's ray meets the triangle's plane (extended
// beyond its edges), where the barycentric mix of the vertex uvs is perspective-correct;
// a bilinear read of the finest level there. Samples whose ray misses the plane are
// left out (if all do — a pixel on the plane's vanishing line — the pixel centre's uv).
glm::dvec3 footprint_average(const core::Texture& tex, int px, int py, const glm::dvec3& eye, const glm::dvec3& fwd,
                             const glm::dvec3& right_step, const glm::dvec3& up_step, const glm::dvec3 P[3],
                             const glm::dvec3& Ng, const glm::dvec2 uv[3], const glm::dvec2& centre_uv, int width,
                             int height) {
  constexpr int kStrata = 16;
  const double Ng2 = glm::dot(Ng, Ng);
  glm::dvec3 sum(0);
  int samples = 0;
  for (int j = 0; j < kStrata; ++j)
    for (int i = 0; i < kStrata; ++i) {
      const uint32_t stratum = uint32_t(j * kStrata + i);
      const double sx = (px + (i + jitter(px, py, stratum)) / kStrata) / width * 2 - 1;
      const double sy = 1 - (py + (j + jitter(py, px, stratum + 7777)) / kStrata) / height * 2;
      const glm::dvec3 dir = fwd + right_step * sx + up_step * sy;
      const double denom = glm::dot(dir, Ng);
      if (denom == 0) continue;
      const double t = glm::dot(P[0] - eye, Ng) / denom;
      if (!(t > 0)) continue;
      const glm::dvec3 X = eye + dir * t;
      const double b0 = glm::dot(glm::cross(P[1] - X, P[2] - X), Ng) / Ng2;
      const double b1 = glm::dot(glm::cross(P[2] - X, P[0] - X), Ng) / Ng2;
      sum += glm::dvec3(tex.bilinear(b0 * uv[0] + b1 * uv[1] + (1 - b0 - b1) * uv[2]));
      ++samples;
    }
  return samples > 0 ? sum / double(samples) : glm::dvec3(tex.bilinear(centre_uv));
}

// ∂h/∂u and ∂h/∂v of the bilinearly interpolated height map (first channel, finest
// level) at uv: the exact derivatives of the surface that core::Texture::bilinear reads.
glm::dvec2 height_gradient(const core::Texture& t, glm::dvec2 uv) {
  // Whole periods off first (a repeating map), or the clamped border: the texel
  // coordinates stay near the map, and their integer parts in int's range.
  if (t.wrap == core::Wrap::Repeat) uv -= glm::floor(uv);
  else uv = glm::clamp(uv, -1.0, 2.0);
  const double s = uv.x * t.width - 0.5, r = (1.0 - uv.y) * t.height - 0.5;
  const double fs = std::floor(s), fr = std::floor(r);
  const double a = s - fs, b = r - fr;
  const int x = int(fs), y = int(fr);
  const double h00 = t.texel(x, y).r, h10 = t.texel(x + 1, y).r;
  const double h01 = t.texel(x, y + 1).r, h11 = t.texel(x + 1, y + 1).r;
  const double dh_ds = (1 - b) * (h10 - h00) + b * (h11 - h01);
  const double dh_dr = (1 - a) * (h01 - h00) + a * (h11 - h10);
  return {dh_ds * t.width, -dh_dr * t.height};  // s grows with u, r against v
}

// The shading normal of a bump-mapped material at a point with unit interpolated normal
// n, texture coordinates uv and the triangle's position derivatives Pu, Pv: Blinn's
// perturbed normal (4) of the exact height field, N' = c·n + Fu (n × Pv) + Fv (Pu × n)
// with c = |Pu × Pv| (his form with the 1/|N| factors, N = c·n), normalized. A material
// that has only a precomputed normal map reads it (bilinear, finest level) in the frame
// of its path. `space` receives N' in the path's frame: world (classic), tangent
// (T = Pu on the tangent plane, B = n × T — times `sign` for the square patch, whose b
// runs along Pv — and n) or object. `sign` is −1 where the parameterization is mirrored
// against the normals (Pu × Pv points inwards): the relief keeps its sign.
glm::dvec3 bump_normal(const core::Scene& scene, const core::Object& object, const core::Material& m,
                       const glm::dvec3& n, const glm::dvec2& uv, const glm::dvec3& Pu, const glm::dvec3& Pv,
                       double sign, glm::dvec3& space) {
  const glm::dvec3 pu_t = Pu - glm::dot(Pu, n) * n;
  const double c = glm::length(glm::cross(Pu, Pv));
  // No frame where the uv triangle has no area, or where the figures leave float's range
  // (as the pipeline decides).
  const bool frame = glm::dot(pu_t, pu_t) > 0 && c > 0 && std::isfinite(float(c)) &&
                     std::isfinite(float(glm::length(Pu))) && std::isfinite(float(glm::length(Pv)));
  const glm::dvec3 T = frame ? glm::normalize(pu_t) : core::any_tangent(n);
  const glm::dvec3 B = (m.path == core::ShadingPath::BumpSquare ? sign : 1.0) * glm::cross(n, T);
  const glm::dmat3 to_object = glm::transpose(glm::dmat3(object.model));
  glm::dvec3 world;
  if (!frame) {
    world = n;  // no tangent frame: the surface is left unperturbed
  } else if (m.height_map < 0) {  // a precomputed normal map only
    const glm::dvec3 stored = glm::normalize(glm::dvec3(scene.textures[m.normal_map].bilinear(uv)));
    world = m.path == core::ShadingPath::BumpObject ? glm::normalize(glm::inverse(to_object) * stored)
                                                    : stored.x * T + stored.y * B + stored.z * n;
  } else {
    const glm::dvec2 F = sign * m.height_scale * height_gradient(scene.textures[m.height_map], uv);
    world = glm::normalize(c * n + F.x * glm::cross(n, Pv) + F.y * glm::cross(Pu, n));
  }
  switch (m.path) {
    case core::ShadingPath::BumpTangent:
    case core::ShadingPath::BumpSquare:
    case core::ShadingPath::BumpObject:
      if (m.path == core::ShadingPath::BumpObject && frame) space = glm::normalize(to_object * world);
      else space = {glm::dot(world, T), glm::dot(world, B), glm::dot(world, n)};  // no frame: a tangent frame
      break;
    default: space = world;
  }
  return world;
}

// An image of the camera's size, its pixels not yet written (clear_row writes them).
Image sized_image(const core::Scene& scene) {
  const core::Camera& cam = scene.camera;
  Image img;
  img.width = cam.width;
  img.height = cam.height;
  const size_t n = size_t(img.width) * img.height;
  img.color.resize(n), img.alpha.resize(n), img.depth.resize(n), img.normal.resize(n);
  for (const core::Object& o : scene.objects)
    if (scene.materials[size_t(o.material)].path == core::ShadingPath::Parallax) img.hit.resize(n);
  return img;
}

// Row y with nothing drawn: the background colour, alpha 0, infinite depth, a zero
// normal (and hit).
void clear_row(Image& img, const core::Scene& scene, int y) {
  const size_t begin = img.index(0, y), end = begin + size_t(img.width);
  std::fill(img.color.begin() + ptrdiff_t(begin), img.color.begin() + ptrdiff_t(end), scene.background);
  std::fill(img.alpha.begin() + ptrdiff_t(begin), img.alpha.begin() + ptrdiff_t(end), 0.0);
  std::fill(img.depth.begin() + ptrdiff_t(begin), img.depth.begin() + ptrdiff_t(end),
            std::numeric_limits<double>::infinity());
  std::fill(img.normal.begin() + ptrdiff_t(begin), img.normal.begin() + ptrdiff_t(end), glm::dvec3(0));
  if (!img.hit.empty()) std::fill(img.hit.begin() + ptrdiff_t(begin), img.hit.begin() + ptrdiff_t(end), glm::dvec3(0));
}

// The camera as the golden model uses it: world → clip, the image size, and the rays
// through the pixel centres.
struct View {
  glm::dmat4 view_projection;
  int width, height;               // the image's, in pixels
  double tan_half, aspect;         // tan(fov_y / 2), width / height
  glm::dvec3 eye, fwd, right, up;  // the camera's position and unit axes
};

// The view of the scene's camera.
View make_view(const core::Camera& cam) {
  View view;
  view.view_projection = cam.projection() * cam.view();
  view.width = cam.width;
  view.height = cam.height;
  // The ray through a pixel centre: eye + t·dir with dir·forward = 1, so that t is the
  // eye-space depth of the point it reaches.
  view.tan_half = std::tan(glm::radians(cam.fov_y_deg) / 2);
  view.aspect = double(cam.width) / cam.height;
  view.eye = cam.position, view.fwd = cam.forward(), view.right = cam.right(), view.up = cam.true_up();
  return view;
}

// A triangle of an object's world-space mesh, with what its pixels need.
struct WorldTriangle {
  glm::dvec3 P[3];    // the vertices' positions
  glm::dvec3 N[3];    // the vertices' unit normals
  glm::dvec2 uv[3];   // the vertices' texture coordinates
  glm::dvec3 Ng;      // (P1 − P0) × (P2 − P0), not normalized
  double Ng2;         // Ng · Ng
  glm::dvec3 Pu, Pv;  // ∂P/∂u, ∂P/∂v (bump and parallax paths; else 0)
  double sign;        // −1: uv mirrored against the normals
};

// Triangle `indices` of `mesh`, with the position derivatives where `material`'s path
// needs them; false for a triangle without area (nothing to draw).
bool setup_triangle(const core::Mesh& mesh, const glm::u32vec3& indices, const core::Material& material,
                    WorldTriangle& tri) {
  auto& P = tri.P;
  P[0] = mesh.positions[indices.x], P[1] = mesh.positions[indices.y], P[2] = mesh.positions[indices.z];
  tri.Ng = glm::cross(P[1] - P[0], P[2] - P[0]);
  tri.Ng2 = glm::dot(tri.Ng, tri.Ng);
  if (!(tri.Ng2 > 0)) return false;
  tri.N[0] = mesh.normals[indices.x], tri.N[1] = mesh.normals[indices.y], tri.N[2] = mesh.normals[indices.z];
  tri.uv[0] = mesh.uvs[indices.x], tri.uv[1] = mesh.uvs[indices.y], tri.uv[2] = mesh.uvs[indices.z];
  // Pu, Pv of the triangle: P1 − P0 = Pu du1 + Pv dv1, P2 − P0 = Pu du2 + Pv dv2
  // (zero where the uv triangle has no area).
  tri.Pu = glm::dvec3(0), tri.Pv = glm::dvec3(0);
  tri.sign = 1;
  if (core::bump_path(material.path) || material.path == core::ShadingPath::Parallax) {
    const glm::dvec2 t1 = tri.uv[1] - tri.uv[0], t2 = tri.uv[2] - tri.uv[0];
    const double det = t1.x * t2.y - t2.x * t1.y;
    if (det != 0) {
      tri.Pu = ((P[1] - P[0]) * t2.y - (P[2] - P[0]) * t1.y) / det;
      tri.Pv = ((P[2] - P[0]) * t1.x - (P[1] - P[0]) * t2.x) / det;
    }
    const glm::dvec3 normals = tri.N[0] + tri.N[1] + tri.N[2];
    if (glm::dot(glm::cross(tri.Pu, tri.Pv), normals) < 0) tri.sign = -1;
  }
  return true;
}

// A pixel centre of a triangle: the depth t of the point X where its ray meets the
// triangle's plane, X, and X's barycentric coordinates.
struct Fragment {
  int px, py;
  double t;
  glm::dvec3 X;
  double b0, b1, b2;
};

// Where the ray through the centre of pixel (px, py) meets the triangle's plane; false
// where it runs inside the plane.
bool make_fragment(const View& view, const WorldTriangle& tri, int px, int py, Fragment& frag) {
  const glm::dvec3& eye = view.eye;
  const auto& P = tri.P;
  const glm::dvec3& Ng = tri.Ng;
  const double sx = (px + 0.5) / view.width * 2 - 1, sy = 1 - (py + 0.5) / view.height * 2;
  const glm::dvec3 dir =
      view.fwd + view.right * (sx * view.tan_half * view.aspect) + view.up * (sy * view.tan_half);
  const double denom = glm::dot(dir, Ng);
  if (denom == 0) return false;  // the ray runs inside the triangle's plane
  double t = glm::dot(P[0] - eye, Ng) / denom;
  glm::dvec3 X = eye + dir * t;
  // Barycentric coordinates of X: sub-triangle areas over the whole.
  double b0 = glm::dot(glm::cross(P[1] - X, P[2] - X), Ng) / tri.Ng2;
  double b1 = glm::dot(glm::cross(P[2] - X, P[0] - X), Ng) / tri.Ng2;
  double b2 = 1 - b0 - b1;
  if (!(t > 0)) {
    // Snapping can cover a pixel centre just outside the triangle; near the
    // plane's vanishing line its ray meets the plane far away or behind the
    // eye. Take the nearest point of the triangle instead (clamped weights).
    b0 = std::max(b0, 0.0), b1 = std::max(b1, 0.0), b2 = std::max(b2, 0.0);
    const double sum = b0 + b1 + b2;
    b0 /= sum, b1 /= sum, b2 /= sum;
    X = b0 * P[0] + b1 * P[1] + b2 * P[2];
    t = glm::dot(X - eye, view.fwd);
  }
  frag = {px, py, t, X, b0, b1, b2};
  return true;
}

// Where the view ray from `eye` through X meets the relief of the material's height map
// (parallax path).
ParallaxHit parallax_trace(const core::Scene& scene, const core::Material& material, const WorldTriangle& tri,
                           const glm::dvec2& uv, const glm::dvec3& X, const glm::dvec3& eye) {
  // The view ray in the relief's frame: Pu, Pv and the normal on the side of
  // the vertex normals, scaled to one uv unit (docs/parallax.md).
  const glm::dvec3 across = glm::cross(tri.Pu, tri.Pv);
  const double area = glm::length(across);
  const glm::dmat3 frame(tri.Pu, tri.Pv, tri.sign * across / area * std::sqrt(area));
  const glm::dvec3 d = glm::inverse(frame) * (X - eye);
  return parallax_hit(scene.textures[material.height_map], uv, d, material.parallax.depth);
}

// The colour texture's value at a fragment with texture coordinates uv (1 without a
// texture): the footprint average on the texturing paths, else one bilinear read at
// tex_uv (on the parallax path where the view ray meets the relief, else uv).
glm::dvec3 texture_value(const core::Scene& scene, const core::Material& material, const View& view,
                         const WorldTriangle& tri, const Fragment& frag, const glm::dvec2& uv,
                         const glm::dvec2& tex_uv) {
  glm::dvec3 tex(1);
  if (material.path == core::ShadingPath::TextureScreen || material.path == core::ShadingPath::TextureObject) {
    tex = footprint_average(scene.textures[material.texture], frag.px, frag.py, view.eye, view.fwd,
                            view.right * (view.tan_half * view.aspect), view.up * view.tan_half, tri.P, tri.Ng,
                            tri.uv, uv, view.width, view.height);
  } else if (material.texture >= 0) {
    tex = glm::dvec3(scene.textures[material.texture].bilinear(tex_uv));
  }
  return tex;
}

// What a drawn pixel receives besides its depth: its colour, and its unit shading
// normal in the space its path lights in (Image::normal).
struct ShadedPixel {
  glm::dvec3 color, normal;
  glm::dvec3 hit{0};  // parallax path: the hit's u, v and height (Image::hit)
};

// Shades a fragment by its material's path: the interpolated normal and uv, the colour
// texture's value, Blinn's perturbed normal on the bump paths, Blinn-Phong.
ShadedPixel shade_fragment(const core::Scene& scene, const core::Object& object, const core::Material& material,
                           const View& view, const WorldTriangle& tri, const Fragment& frag) {
  const double b0 = frag.b0, b1 = frag.b1, b2 = frag.b2;
  const glm::dvec3 N = glm::normalize(b0 * tri.N[0] + b1 * tri.N[1] + b2 * tri.N[2]);
  const glm::dvec2 uv = b0 * tri.uv[0] + b1 * tri.uv[1] + b2 * tri.uv[2];
  ShadedPixel shaded;
  glm::dvec2 tex_uv = uv;
  if (material.path == core::ShadingPath::Parallax) {
    shaded.hit = glm::dvec3(uv, 1.0);  // untraced: the polygon itself
    if (glm::length(glm::cross(tri.Pu, tri.Pv)) > 0) {
      const ParallaxHit hit = parallax_trace(scene, material, tri, uv, frag.X, view.eye);
      tex_uv = hit.uv;
      shaded.hit = glm::dvec3(hit.uv, hit.height);
    }
  }
  const glm::dvec3 tex = texture_value(scene, material, view, tri, frag, uv, tex_uv);
  if (core::bump_path(material.path)) {
    const glm::dvec3 bumped = bump_normal(scene, object, material, N, uv, tri.Pu, tri.Pv, tri.sign, shaded.normal);
    shaded.color = shade(scene, material, frag.X, bumped, tex);
  } else {
    shaded.normal = N;
    shaded.color = shade(scene, material, frag.X, N, tex);
  }
  return shaded;
}

// Writes a drawn pixel: its depth, full coverage, its normal and colour.
void write_pixel(Image& img, size_t i, double depth, const ShadedPixel& shaded) {
  img.depth[i] = depth;
  img.alpha[i] = 1;
  img.normal[i] = shaded.normal;
  img.color[i] = shaded.color;
  if (!img.hit.empty()) img.hit[i] = shaded.hit;
}

// Draws pixel (px, py) of a triangle that covers it, where it is nearer than what the
// pixel holds (ties keep the first).
void draw_pixel(const core::Scene& scene, const core::Object& object, const core::Material& material,
                const View& view, const WorldTriangle& tri, int px, int py, Image& img) {
  Fragment frag;
  if (!make_fragment(view, tri, px, py, frag)) return;
  const size_t i = img.index(px, py);
  if (!(frag.t < img.depth[i])) return;
  write_pixel(img, i, frag.t, shade_fragment(scene, object, material, view, tri, frag));
}

// The rows of the image one thread draws: bands of kBandRows rows, every parts-th band
// from its part on (interleaved, so that an object on one side of the frame is shared).
struct Rows {
  int part = 0, parts = 1;
  bool own(int y) const { return (y / kBandRows) % parts == part; }
};

// Draws a triangle: clipped to the view volume, each piece snapped, culled if the object
// asks, and every pixel it covers in `rows` drawn (core/coverage.hpp).
void draw_triangle(const core::Scene& scene, const core::Object& object, const core::Material& material,
                   const View& view, const WorldTriangle& tri, Image& img, Rows rows) {
  const auto poly = core::clip_triangle(view.view_projection * glm::dvec4(tri.P[0], 1),
                                        view.view_projection * glm::dvec4(tri.P[1], 1),
                                        view.view_projection * glm::dvec4(tri.P[2], 1));
  for (size_t k = 1; k + 1 < poly.size(); ++k) {
    core::SnappedTriangle st;
    if (!core::snap_triangle(core::to_screen(poly[0].clip, img.width, img.height),
                             core::to_screen(poly[k].clip, img.width, img.height),
                             core::to_screen(poly[k + 1].clip, img.width, img.height),
                             img.width, img.height, st))
      continue;
    if (object.cull_back && !st.front_facing) continue;
    for (int py = st.y0; py <= st.y1; ++py) {
      if (!rows.own(py)) continue;
      const auto [x_begin, x_end] = st.row_span(py);
      for (int px = x_begin; px < x_end; ++px) draw_pixel(scene, object, material, view, tri, px, py, img);
    }
  }
}

// Draws every triangle of an object (its mesh in world space) into `rows`.
void draw_object(const core::Scene& scene, const core::Object& object, const core::Mesh& mesh, const View& view,
                 Image& img, Rows rows) {
  const core::Material& material = scene.materials[object.material];
  for (const auto& indices : mesh.triangles) {
    WorldTriangle tri;
    if (setup_triangle(mesh, indices, material, tri)) draw_triangle(scene, object, material, view, tri, img, rows);
  }
}

}  // namespace

Image render(const core::Scene& scene, int threads) {
  Image img = sized_image(scene);
  const View view = make_view(scene.camera);
  std::vector<core::Mesh> meshes;
  for (const core::Object& object : scene.objects) meshes.push_back(core::to_world(object));
  const int bands = (img.height + kBandRows - 1) / kBandRows;
  const int parts = std::max(1, std::min(core::threads_or_cores(threads), bands));
  core::run_parts(parts, [&](int part) {
    const Rows rows{part, parts};
    for (int y = 0; y < img.height; ++y)
      if (rows.own(y)) clear_row(img, scene, y);
    for (size_t k = 0; k < scene.objects.size(); ++k) draw_object(scene, scene.objects[k], meshes[k], view, img, rows);
  });
  return img;
}

std::map<std::string, std::string> truth(const core::Scene& scene) {
  std::map<std::string, std::string> t;
  for (const core::Object& o : scene.objects) {
    const core::Material& m = scene.materials[size_t(o.material)];
    if (core::bump_path(m.path)) t[m.name] = m.height_map < 0 ? "normal map" : "height field";
    if (m.path == core::ShadingPath::Parallax) t[m.name] = "height field";
  }
  return t;
}

core::Frame to_frame(const Image& img, int threads) {
  // A layer: its name and where its values stand in the image (a component of a vector
  // buffer, or a scalar buffer).
  struct Layer {
    const char* name;
    const Buffer<glm::dvec3>* vectors;
    int component;
    const Buffer<double>* scalars;
    double at(size_t i) const { return vectors ? (*vectors)[i][component] : (*scalars)[i]; }
  };
  std::vector<Layer> layers = {{"R", &img.color, 0, nullptr},   {"G", &img.color, 1, nullptr},
                               {"B", &img.color, 2, nullptr},   {"A", nullptr, 0, &img.alpha},
                               {"Z", nullptr, 0, &img.depth},   {"N.X", &img.normal, 0, nullptr},
                               {"N.Y", &img.normal, 1, nullptr}, {"N.Z", &img.normal, 2, nullptr}};
  if (!img.hit.empty())
    layers.insert(layers.end(), {{"parallax.u", &img.hit, 0, nullptr}, {"parallax.v", &img.hit, 1, nullptr},
                                 {"parallax.height", &img.hit, 2, nullptr}});
  core::Frame f(img.width, img.height);
  f.channels.resize(layers.size());
  // Each layer converted whole by one thread, which first touches its pages (at 1080p
  // the layers are 8 MB each).
  const int parts = std::max(1, std::min(core::threads_or_cores(threads), int(layers.size())));
  core::run_parts(parts, [&](int part) {
    for (size_t k = size_t(part); k < layers.size(); k += size_t(parts)) {
      std::vector<float> values(f.pixel_count());
      for (size_t i = 0; i < values.size(); ++i) values[i] = float(layers[k].at(i));
      f.channels[k] = {layers[k].name, std::move(values)};
    }
  });
  return f;
}

}  // namespace shadetlm::reference
