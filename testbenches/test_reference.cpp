// The golden model against closed forms: quads whose every pixel has an exact normal,
// depth and Blinn-Phong colour computable here by hand, each within 1e-9.
#include <cmath>
#include <cstring>
#include <functional>

#include "shadetlm/core/compare.hpp"
#include "shadetlm/reference/reference.hpp"
#include "test_util.hpp"

using namespace shadetlm;  // core::, modules::, reference::

namespace {
constexpr double kTol = 1e-9;

core::Camera camera(glm::dvec3 pos, glm::dvec3 target, int w, int h, double fov, bool local) {
  core::Camera c;
  c.position = pos;
  c.target = target;
  c.width = w;
  c.height = h;
  c.fov_y_deg = fov;
  c.near = 0.1;
  c.far = 100;
  c.local_viewer = local;
  return c;
}

core::Material material() {
  core::Material m;
  m.ambient = {0.2, 0.3, 0.4};
  m.diffuse = {0.7, 0.5, 0.3};
  m.specular = {0.5, 0.6, 0.7};
  m.shininess = 20;
  return m;
}

// The ray through the centre of pixel (x, y), with a unit component along the view axis.
glm::dvec3 pixel_ray(const core::Camera& c, int x, int y) {
  const glm::dvec3 f = glm::normalize(c.target - c.position);
  const glm::dvec3 r = glm::normalize(glm::cross(f, c.up));
  const glm::dvec3 u = glm::cross(r, f);
  const double th = std::tan(c.fov_y_deg * M_PI / 360.0);
  const double sx = (2.0 * (x + 0.5) / c.width - 1) * th * c.width / c.height;
  const double sy = (1 - 2.0 * (y + 0.5) / c.height) * th;
  return f + sx * r + sy * u;
}

// Blinn-Phong, written out for one light.
glm::dvec3 blinn_phong(const core::Material& m, glm::dvec3 ambient, glm::dvec3 radiance, glm::dvec3 N,
                       glm::dvec3 L, glm::dvec3 V) {
  glm::dvec3 c = ambient * m.ambient;
  const double nl = glm::dot(N, L);
  if (nl > 0) {
    const double nh = std::max(0.0, glm::dot(N, glm::normalize(L + V)));
    c += radiance * (m.diffuse * nl + m.specular * std::pow(nh, m.shininess));
  }
  return c;
}

void check_close(glm::dvec3 got, glm::dvec3 want) {
  for (int k = 0; k < 3; ++k) CHECK(std::abs(got[k] - want[k]) <= kTol);
}
}  // namespace

TEST_CASE("a quad facing the camera under a directional light, viewer at infinity", "[reference]") {
  core::Scene s;
  s.camera = camera({0, 0, 5}, {0, 0, 0}, 40, 30, 60, false);
  s.ambient = {0.1, 0.1, 0.1};
  core::Light sun;
  sun.direction = glm::normalize(glm::dvec3(-1, -1, -2));
  sun.color = {1, 0.9, 0.8};
  sun.intensity = 1.5;
  s.lights = {sun};
  s.materials = {material()};
  core::Object quad;  // 100 × 100: far beyond the view, so it is clipped by the guard band
  quad.mesh = core::make_plane({100, 100}, {3, 3});
  s.objects.push_back(quad);

  const reference::Image img = reference::render(s);
  const glm::dvec3 N(0, 0, 1), L = -sun.direction, V(0, 0, 1);
  const glm::dvec3 want = blinn_phong(s.materials[0], s.ambient, sun.radiance(), N, L, V);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const size_t i = img.index(x, y);
      REQUIRE(img.alpha[i] == 1);
      check_close(img.color[i], want);
      check_close(img.normal[i], N);
      CHECK(std::abs(img.depth[i] - 5.0) <= kTol);
    }
}

TEST_CASE("an oblique quad with varying normals, a point light and a local viewer", "[reference]") {
  core::Scene s;
  s.camera = camera({0.3, -4, 3}, {0, 0.5, 0}, 64, 48, 50, true);
  s.ambient = {0.05, 0.05, 0.05};
  core::Light lamp;
  lamp.type = core::Light::Type::Point;
  lamp.position = {1, 1, 2};
  lamp.color = {0.9, 1, 0.8};
  lamp.intensity = 2;
  s.lights = {lamp};
  s.materials = {material()};
  // Two triangles, A B D (where x ≥ y) and A D C (where x ≤ y), with four different
  // unit vertex normals: perspective-correct interpolation is what gets tested.
  const double h = 3;
  const glm::dvec3 n[4] = {glm::normalize(glm::dvec3(0.3, -0.2, 1)), glm::normalize(glm::dvec3(-0.4, 0.1, 1)),
                           glm::normalize(glm::dvec3(0.2, 0.5, 1)), glm::normalize(glm::dvec3(-0.1, -0.3, 1))};
  core::Object quad;
  const glm::dvec2 corner[4] = {{-h, -h}, {h, -h}, {-h, h}, {h, h}};
  for (int k = 0; k < 4; ++k)
    quad.mesh.add({corner[k], 0}, n[k], {core::any_tangent(n[k]), 1}, (corner[k] + h) / (2 * h));
  quad.mesh.triangles = {{0, 1, 3}, {0, 3, 2}};
  s.objects.push_back(quad);

  const reference::Image img = reference::render(s);
  int covered = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const size_t i = img.index(x, y);
      const glm::dvec3 dir = pixel_ray(s.camera, x, y);
      const double t = -s.camera.position.z / dir.z;
      const glm::dvec3 P = s.camera.position + t * dir;
      const bool inside = t > 0 && std::abs(P.x) < h + 0.05 && std::abs(P.y) < h + 0.05;
      // Snapping moves edges by at most 1/512 pixel: only pixels well inside must be
      // covered, and only pixels inside may be.
      const bool well_inside = t > 0 && std::abs(P.x) < h - 0.05 && std::abs(P.y) < h - 0.05;
      if (well_inside) CHECK(img.alpha[i] == 1);
      if (img.alpha[i] == 0) continue;
      REQUIRE(inside);
      ++covered;
      // Barycentric weights of P in its triangle, in the plane z = 0.
      const glm::dvec2 q = (glm::dvec2(P) + h) / (2 * h);  // [0,1]² across the quad
      glm::dvec3 N;
      if (q.x >= q.y)  // A B D: P = A + (B−A)·(q.x − q.y) + (D−A)·q.y … in weights:
        N = (1 - q.x) * n[0] + (q.x - q.y) * n[1] + q.y * n[3];
      else             // A D C
        N = (1 - q.y) * n[0] + q.x * n[3] + (q.y - q.x) * n[2];
      N = glm::normalize(N);
      const glm::dvec3 L = glm::normalize(lamp.position - P);
      const glm::dvec3 V = glm::normalize(s.camera.position - P);
      check_close(img.normal[i], N);
      check_close(img.color[i], blinn_phong(s.materials[0], s.ambient, lamp.radiance(), N, L, V));
      CHECK(std::abs(img.depth[i] - t) <= kTol);
    }
  CHECK(covered > img.width * img.height / 3);
}

TEST_CASE("the nearer surface wins whatever the drawing order", "[reference]") {
  for (bool near_first : {true, false}) {
    core::Scene s;
    s.camera = camera({0, 0, 5}, {0, 0, 0}, 16, 16, 40, true);
    core::Material red = material(), blue = material();
    red.ambient = {1, 0, 0};
    blue.ambient = {0, 0, 1};
    s.ambient = {1, 1, 1};
    s.materials = {red, blue};
    core::Object a, b;
    a.mesh = core::make_plane({10, 10}, {1, 1});
    a.model = glm::dmat4(1);
    a.model[3] = glm::dvec4(0, 0, 1, 1);  // nearer
    a.material = 0;
    b.mesh = core::make_plane({10, 10}, {1, 1});
    b.material = 1;
    s.objects = near_first ? std::vector<core::Object>{a, b} : std::vector<core::Object>{b, a};
    const reference::Image img = reference::render(s);
    for (size_t i = 0; i < img.color.size(); ++i) {
      CHECK(img.color[i] == glm::dvec3(1, 0, 0));
      CHECK(std::abs(img.depth[i] - 4) <= kTol);
    }
  }
}

TEST_CASE("back faces are culled only when the object asks", "[reference]") {
  core::Scene s;
  s.camera = camera({0, 0, -5}, {0, 0, 0}, 8, 8, 40, true);  // behind the +z-facing plane
  s.materials = {material()};
  core::Object quad;
  quad.mesh = core::make_plane({10, 10}, {1, 1});
  s.objects = {quad};
  CHECK(reference::render(s).alpha[0] == 1);
  s.objects[0].cull_back = true;
  CHECK(reference::render(s).alpha[0] == 0);
}

TEST_CASE("the golden model draws the same image on any number of threads", "[reference]") {
  // Overlapping objects (the knot over itself, ties kept by the first drawn) and a
  // parallax material: each thread draws every triangle into its own bands of rows.
  for (const char* file : {"golden/knot/scene.json", "golden/parallax-steps/scene.json", "golden/demo/scene.json"}) {
    const core::Scene scene = core::load_scene(test::source_path(file));
    const reference::Image one = reference::render(scene, 1);
    for (int threads : {2, 3, 7}) {
      const reference::Image many = reference::render(scene, threads);
      INFO(file << " on " << threads << " threads");
      CHECK(many.color == one.color);
      CHECK(many.depth == one.depth);
      CHECK(many.alpha == one.alpha);
      CHECK(many.normal == one.normal);
      CHECK(many.hit == one.hit);
    }
  }
}

TEST_CASE("the golden model's frame and its comparison are the same on any number of threads", "[reference]") {
  // to_frame converts a layer a thread, compare_frames measures a layer a thread: the
  // frame and every figure must not depend on the count (parallax-steps has 11 layers).
  for (const char* file : {"golden/parallax-steps/scene.json", "golden/demo/scene.json"}) {
    const core::Scene scene = core::load_scene(test::source_path(file));
    const reference::Image image = reference::render(scene, 1);
    const core::Frame one = reference::to_frame(image, 1);
    // Each layer is its own component of the image, converted, at every pixel.
    const std::pair<const char*, std::function<double(size_t)>> layers[] = {
        {"R", [&](size_t i) { return image.color[i][0]; }},  {"G", [&](size_t i) { return image.color[i][1]; }},
        {"B", [&](size_t i) { return image.color[i][2]; }},  {"A", [&](size_t i) { return image.alpha[i]; }},
        {"Z", [&](size_t i) { return image.depth[i]; }},     {"N.X", [&](size_t i) { return image.normal[i][0]; }},
        {"N.Y", [&](size_t i) { return image.normal[i][1]; }}, {"N.Z", [&](size_t i) { return image.normal[i][2]; }}};
    for (const auto& [name, value] : layers) {
      size_t wrong = 0;
      for (size_t i = 0; i < one.pixel_count(); ++i) wrong += !(one.at(name)[i] == float(value(i)) || std::isnan(value(i)));
      INFO(name);
      CHECK(wrong == 0);
    }
    if (!image.hit.empty())
      for (int k = 0; k < 3; ++k) {
        const char* name = k == 0 ? "parallax.u" : k == 1 ? "parallax.v" : "parallax.height";
        size_t wrong = 0;
        for (size_t i = 0; i < one.pixel_count(); ++i) wrong += one.at(name)[i] != float(image.hit[i][k]);
        INFO(name);
        CHECK(wrong == 0);
      }
    // A second frame that differs in every layer, so that every figure is non-trivial.
    core::Frame other = one;
    for (size_t k = 0; k < other.channels.size(); ++k)
      for (size_t i = 0; i < other.pixel_count(); ++i)
        other.channels[k].values[i] += std::ldexp(float((i * 7 + k) % 13), -12);
    core::CompareOptions o;
    o.fail = 0;
    const core::CompareResult alone = core::compare_frames(other, one, o);
    for (int threads : {2, 3, 16}) {
      INFO(file << " on " << threads << " threads");
      const core::Frame many = reference::to_frame(image, threads);
      REQUIRE(many.channels.size() == one.channels.size());
      for (size_t k = 0; k < one.channels.size(); ++k) {
        CHECK(many.channels[k].name == one.channels[k].name);
        CHECK(std::memcmp(many.channels[k].values.data(), one.channels[k].values.data(),
                          one.channels[k].values.size() * sizeof(float)) == 0);
      }
      o.threads = threads;
      const core::CompareResult shared = core::compare_frames(other, one, o);
      REQUIRE(shared.layers.size() == alone.layers.size());
      CHECK(shared.pass == alone.pass);
      for (size_t k = 0; k < alone.layers.size(); ++k) {
        const core::LayerMetrics &a = alone.layers[k], &b = shared.layers[k];
        CHECK(b.layer == a.layer);
        CHECK(b.pixels == a.pixels);
        CHECK(b.over == a.over);
        CHECK(b.max_x == a.max_x);
        CHECK(b.max_y == a.max_y);
        CHECK(std::memcmp(&b.rmse, &a.rmse, sizeof(double)) == 0);  // bit for bit (NaN too)
        CHECK(std::memcmp(&b.frame_rmse, &a.frame_rmse, sizeof(double)) == 0);
        CHECK(std::memcmp(&b.max_abs, &a.max_abs, sizeof(double)) == 0);
      }
    }
    for (const core::LayerMetrics& m : alone.layers) {  // (the figures compared above are not 0)
      INFO(m.layer);
      CHECK(m.frame_rmse > 0);
    }
  }
}
