// Object-space texturing (docs/object-space-texturing.md): the rotation of (1)–(7),
// texel_project's splats (no holes, weights that sum to 1, a constant texture stays
// constant, one LOD per polygon), the screen-space filters it competes with, and
// hostile geometry.
#include <cmath>
#include <cstring>
#include <random>
#include <sstream>

#include "shadetlm/core/bump_map.hpp"
#include "shadetlm/core/compare.hpp"
#include "shadetlm/modules/pipeline/pipeline.hpp"
#include "shadetlm/modules/texel_project/texel_project_kernel.hpp"
#include "shadetlm/reference/reference.hpp"
#include "shadetlm/sampling/sampler.hpp"
#include "systemc_harness.hpp"
#include "test_util.hpp"

using namespace shadetlm;  // core::, modules::, reference::

namespace {

// A textured plane seen from `elevation` degrees above it (90: facing the camera).
std::string plane_scene(const std::string& path, double elevation, const std::string& texture = "") {
  const double e = elevation * M_PI / 180, distance = 2.4;
  const std::string tex = texture.empty() ? R"({"type": "checker", "size": [64, 64], "cells": 8})" : texture;
  return R"({"format": 1,
    "camera": {"position": [0, )" + std::to_string(distance * std::sin(e)) + ", " + std::to_string(distance * std::cos(e)) +
         R"(], "target": [0, 0, 0], "resolution": [96, 72], "near": 0.05, "local_viewer": false},
    "ambient": [0.2, 0.2, 0.2],
    "lights": [{"type": "directional", "direction": [-0.3, -0.8, -0.5]}],
    "textures": {"t": )" + tex + R"(},
    "materials": {"m": {"texture": "t", "path": ")" + path + R"(", "ambient": [1, 1, 1]}},
    "objects": [{"shape": "plane", "size": [2, 2], "tessellation": [4, 4], "material": "m",
                 "transform": {"rotate": [-90, 0, 0]}}]})";
}

const nlohmann::json& details(const modules::RenderResult& r, const std::string& block) {
  for (const auto& b : r.blocks)
    if (b.name == block) return b.details;
  static const nlohmann::json none;
  return none;
}

}  // namespace

TEST_CASE("the rotation of (1)-(2) lays every triangle parallel to XY, d = 0 included", "[texturing]") {
  const glm::dvec3 normals[] = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {-1, 0, 0}, {0, 1, 0},
                                glm::normalize(glm::dvec3(1, 2, 3)), glm::normalize(glm::dvec3(-0.2, 0.9, -0.1))};
  for (const glm::dvec3& n : normals) {
    INFO("n = " << n.x << ", " << n.y << ", " << n.z);
    const modules::PolygonRotation R(n);
    const glm::dvec3 rn = R.apply(n, n);  // R·n = +z
    CHECK(std::abs(rn.x) < 1e-12);
    CHECK(std::abs(rn.y) < 1e-12);
    CHECK(rn.z == Approx(1).epsilon(1e-12));
    // z' is the same for every point of the plane, so (7) computes it once.
    const glm::dvec3 t = glm::normalize(glm::cross(n, glm::dvec3(0.3, 0.5, 0.7)));
    const glm::dvec3 a(0.4, -1.1, 2.0), b = a + 1.7 * t + 0.3 * glm::cross(n, t);
    CHECK(R.apply(a, n).z == Approx(R.apply(b, n).z).margin(1e-12));
    // [R]⁻¹ = Rᵀ takes the rotated point back.
    const glm::dvec3 back = R.inverse(R.apply(b, n), n);
    CHECK(glm::length(back - b) < 1e-12);
  }
}

TEST_CASE("texel_project: no holes, weights that sum to 1, one LOD per polygon", "[texturing]") {
  for (double elevation : {80.0, 45.0, 15.0, 5.0}) {
    INFO("elevation " << elevation);
    const modules::RenderResult r = modules::render_loop(core::load_scene_text(plane_scene("texture-object", elevation), "p", "."));
    const nlohmann::json& d = details(r, "texel_project");
    REQUIRE(!d.is_null());
    CHECK(d["covered_pixels"].get<uint64_t>() == r.pixels_shaded);
    CHECK(d["holes"].get<uint64_t>() == 0);
    CHECK(d["weight_sum_error"].get<double>() < 1e-6);
    CHECK(d["lod_computations"].get<uint64_t>() == d["polygons"].get<uint64_t>());
    CHECK(d["polygons"].get<uint64_t>() <= 32);  // 4 × 4 quads
    CHECK(test::no_nan(r.frame));
  }
  // The paper's LOD rule (constant z′): also one per polygon, no holes; facing the camera
  // it picks what the most magnified vertex does (within the plane's perspective), and
  // at grazing views a finer level — z′, the plane's distance, is below every vertex's
  // depth — so at least as many texels. It is measured from the eye: moving the scene and
  // the camera together changes nothing.
  struct Lod {
    uint64_t texels, magnified;
  };
  auto texels = [](double elevation, const std::string& rule, const std::vector<std::string>& more = {}) {
    std::vector<std::string> sets = {"pipeline.texel_project.lod=" + rule};
    sets.insert(sets.end(), more.begin(), more.end());
    const modules::RenderResult r =
        modules::render_loop(core::load_scene_text(plane_scene("texture-object", elevation), "p", ".", sets));
    const nlohmann::json& d = details(r, "texel_project");
    CHECK(d["holes"].get<uint64_t>() == 0);
    CHECK(d["lod_rule"] == rule);
    CHECK(d["lod_computations"].get<uint64_t>() == d["polygons"].get<uint64_t>());
    return Lod{d["texels"].get<uint64_t>(), d["magnified_polygons"].get<uint64_t>()};
  };
  for (double elevation : {80.0, 45.0, 15.0, 5.0}) {
    INFO("elevation " << elevation);
    const Lod z = texels(elevation, "constant-z"), vertex = texels(elevation, "most-magnified");
    CHECK(z.texels >= vertex.texels);
    if (elevation == 80.0) CHECK(double(z.texels) <= 4.0 * double(vertex.texels));  // at most one level finer
    const double e = elevation * M_PI / 180;
    std::ostringstream eye;
    eye << "camera.position=[100," << -40 + 2.4 * std::sin(e) << "," << 7 + 2.4 * std::cos(e) << "]";
    const Lod moved = texels(elevation, "constant-z", {"objects.0.transform.translate=[100,-40,7]", eye.str(),
                                                       "camera.target=[100,-40,7]"});
    CHECK(moved.magnified == z.magnified);
    CHECK(double(moved.texels) == Approx(double(z.texels)).epsilon(0.02));  // float visibility at the edges
  }
  // The screen-space filters compute a LOD per pixel.
  const modules::RenderResult s = modules::render_loop(core::load_scene_text(plane_scene("texture-screen", 30), "s", "."));
  CHECK(details(s, "texture_fetch")["lod_computations"].get<uint64_t>() == s.pixels_shaded);
}

TEST_CASE("a constant texture gives its constant, through the splats and every screen filter", "[texturing]") {
  const std::string grey = R"({"type": "checker", "size": [32, 32], "cells": 4, "colors": [[0.4, 0.5, 0.6], [0.4, 0.5, 0.6]]})";
  // The same scene lit with the texture read once per pixel (phong): the reference here.
  const core::Frame expected = modules::render_loop(core::load_scene_text(plane_scene("phong", 35, grey), "g", ".")).frame;
  auto check = [&](const std::string& path, const std::vector<std::string>& sets) {
    INFO(path << (sets.empty() ? "" : " " + sets[0]));
    const core::Frame f = modules::render_loop(core::load_scene_text(plane_scene(path, 35, grey), "g", ".", sets)).frame;
    double worst = 0;
    for (const char* c : {"R", "G", "B"})
      for (size_t i = 0; i < f.pixel_count(); ++i)
        worst = std::max(worst, double(std::abs(f.at(c)[i] - expected.find(c)->values[i])));
    CHECK(worst < 1e-5);  // float rounding of Σ s·c / Σ s and of the filter weights
  };
  check("texture-object", {});
  for (const char* filter : {"nearest", "bilinear", "trilinear", "anisotropic", "ewa"})
    check("texture-screen", {std::string("pipeline.texture_fetch.filter=") + filter});
}

TEST_CASE("object-space texturing beats trilinear filtering at a grazing angle", "[texturing][accuracy]") {
  // The paper's claim 1 on a checker at 15° elevation, against the footprint-averaged golden model.
  auto psnr = [](const std::string& path, const std::vector<std::string>& sets) {
    const core::Scene scene = core::load_scene_text(plane_scene(path, 15), "c", ".", sets);
    core::CompareOptions o;
    o.layers = {"RGB"};
    return core::compare_frames(modules::render_loop(scene).frame, reference::to_frame(reference::render(scene)), o)
        .layers.at(0)
        .psnr;
  };
  const double object = psnr("texture-object", {});
  const double trilinear = psnr("texture-screen", {"pipeline.texture_fetch.filter=trilinear"});
  INFO("object space " << object << " dB, trilinear " << trilinear << " dB");
  CHECK(object > trilinear);
}

TEST_CASE("texturing with hostile geometry and textures: edge-on, across the near plane, 1x1, odd sizes", "[texturing]") {
  const std::string one = R"({"type": "checker", "size": [1, 1], "cells": 1})";
  const std::string narrow = R"({"type": "checker", "size": [64, 4], "cells": 4})";
  struct Case {
    std::string name, text;
    std::vector<std::string> sets;
  };
  const std::vector<Case> cases = {
      {"edge-on", plane_scene("texture-object", 0), {}},
      {"edge-on screen", plane_scene("texture-screen", 0), {"pipeline.texture_fetch.filter=ewa"}},
      {"across the near plane", plane_scene("texture-object", 30), {"camera.position=[0,0.05,0.6]", "camera.near=0.1"}},
      {"across the near plane, screen", plane_scene("texture-screen", 30),
       {"camera.position=[0,0.05,0.6]", "camera.near=0.1", "pipeline.texture_fetch.filter=anisotropic"}},
      {"1x1 texture", plane_scene("texture-object", 40, one), {}},
      {"1x1 texture, screen", plane_scene("texture-screen", 40, one), {"pipeline.texture_fetch.filter=ewa"}},
      {"64x4 texture", plane_scene("texture-object", 40, narrow), {}},
      {"64x4 texture, screen", plane_scene("texture-screen", 40, narrow), {"pipeline.texture_fetch.filter=ewa"}},
      {"degenerate uv", plane_scene("texture-object", 40), {"objects.0.uv_repeat=[1e-30,1e-30]"}},
  };
  for (const Case& c : cases) {
    INFO(c.name);
    const core::Scene scene = core::load_scene_text(c.text, "h", ".", c.sets);
    const modules::RenderResult r = modules::render_loop(scene);
    CHECK(test::no_nan(r.frame));
    CHECK(test::no_nan(reference::to_frame(reference::render(scene))));
    const nlohmann::json& d = details(r, "texel_project");
    if (!d.is_null()) CHECK(d["holes"].get<uint64_t>() == 0);
  }
}

TEST_CASE("texturing paths reject textures whose sides are not powers of two", "[texturing]") {
  const auto e = test::scene_error(plane_scene("texture-object", 40, R"({"type": "checker", "size": [37, 23], "cells": 5})"));
  CHECK(std::string(e.what()).find("materials.m.texture") != std::string::npos);
  CHECK(std::string(e.what()).find("power-of-two") != std::string::npos);
}

TEST_CASE("a triangle whose uv has no area takes the texture's value there, not black", "[texturing]") {
  // Every uv the same: the texture is constant over the plane, its value at that uv.
  const std::string text = plane_scene("texture-object", 40, R"({"type": "checker", "size": [4, 4], "cells": 2,
      "colors": [[0.2, 0.6, 0.9], [0.9, 0.1, 0.1]]})");
  const core::Scene scene = core::load_scene_text(text, "d", ".", {"objects.0.uv_repeat=[1e-30,1e-30]"});
  const modules::RenderResult r = modules::render_loop(scene);
  const core::Frame ref = reference::to_frame(reference::render(scene));
  core::CompareOptions o;
  o.layers = {"RGB"};
  CHECK(core::compare_frames(r.frame, ref, o).layers.at(0).max_abs < 1e-4);
  CHECK(details(r, "texel_project")["holes"].get<uint64_t>() == 0);
}

TEST_CASE("texturing paths: SystemC pipeline and plain loop give the same bits", "[texturing][systemc]") {
  test::route_systemc_reports_to_failures();
  std::string text = plane_scene("texture-object", 30);
  // A second material on a sphere: screen-space, anisotropic; a third: phong with the texture.
  text.replace(text.find(R"("materials": {)"), 14,
               R"("materials": {"s": {"texture": "t", "path": "texture-screen"}, "p": {"texture": "t"}, )");
  text.replace(text.rfind("]}"), 2, R"(, {"shape": "sphere", "radius": 0.3, "material": "s", "transform": {"translate": [0.4, 0.3, 0]}},
      {"shape": "sphere", "radius": 0.25, "material": "p", "transform": {"translate": [-0.5, 0.3, 0.2]}}]})");
  const core::Scene scene = core::load_scene_text(text, "all", ".", {"pipeline.texture_fetch.filter=anisotropic"});
  const modules::RenderResult sc = modules::render_systemc(scene);
  const modules::RenderResult loop = modules::render_loop(scene);
  for (const auto& c : sc.frame.channels) {
    INFO(c.name);
    CHECK(std::memcmp(c.values.data(), loop.frame.at(c.name).data(), c.values.size() * sizeof(float)) == 0);
  }
  CHECK(sc.total_ops() == loop.total_ops());
  CHECK(sc.blocks.back().name == "texel_project");
  // The second pass ends the frame, after everything of the first.
  CHECK(sc.frame_cycles == uint64_t(sc.blocks.back().last_cycle + 1));
  for (size_t i = 0; i + 1 < sc.blocks.size(); ++i) CHECK(sc.blocks[i].last_cycle < sc.blocks.back().last_cycle);
}

// The texture unit's declared operation counts (what bump_fetch and texture_fetch put in
// the stats' ops) against what its code does, the filter run on Counted<float>: every
// filter, both wraps, footprints from magnified through 16 : 1 to degenerate, per sample
// and per span. The counted run's values are float32's, bit for bit.
TEST_CASE("the texture unit's declared operation counts are what its code counts", "[texturing][ops]") {
  using C = modules::Counted<float>;
  core::ProceduralParams pp;
  pp.size = {64, 32}, pp.color_a = {1, 0.5, 0.25};
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> position(-2.0f, 3.0f), exponent(-5.0f, 0.5f), coin(0.0f, 1.0f);
  // A derivative: 0 now and then, else ±10^e per pixel step (up to ~3 textures a pixel).
  auto derivative = [&] { return coin(rng) < 0.1f ? 0.0f : (coin(rng) < 0.5f ? -1 : 1) * std::pow(10.0f, exponent(rng)); };
  for (core::Wrap wrap : {core::Wrap::Repeat, core::Wrap::Clamp}) {
    core::Texture base = core::make_value_noise(pp);
    base.wrap = wrap;
    std::vector<core::Texture> levels = core::mip_levels(base, false);
    modules::MipMap map;
    map.levels.push_back(&base);
    for (auto& l : levels) l.wrap = wrap, map.levels.push_back(&l);
    for (int f = 0; f < int(modules::filter_names().size()); ++f) {
      const auto filter = modules::Filter(f);
      INFO("filter " << modules::filter_names()[size_t(f)] << (wrap == core::Wrap::Repeat ? " repeat" : " clamp"));
      modules::Sampler counted(filter, 8), plain(filter, 8);
      for (int i = 0; i < 3000; ++i) {
        const float u = position(rng), v = position(rng);
        const float d[4] = {derivative(), derivative(), derivative(), derivative()};
        modules::Ops declared, plain_ops;
        C::ops = {};
        C out[3];
        counted.sample_as<C>(map, u, v, d[0], d[1], d[2], d[3], out, declared);
        float expected[3];
        plain.sample(map, u, v, d[0], d[1], d[2], d[3], expected, plain_ops);
        INFO("sample " << i << " uv " << u << ' ' << v << " d " << d[0] << ' ' << d[1] << ' ' << d[2] << ' ' << d[3]
                       << ": " << test::arithmetic_diff(declared, C::ops));
        REQUIRE(test::same_arithmetic(declared, C::ops));
        REQUIRE(declared == plain_ops);
        for (int c = 0; c < 3; ++c) REQUIRE(std::memcmp(&out[c].v, &expected[c], sizeof(float)) == 0);
      }
      // A span of a perspective triangle: uv and its derivatives per pixel, the planes'
      // seeds per span.
      modules::TriangleSetup t;
      t.x_ref = 3, t.y_ref = 5;
      t.inv_w = {0.8f, 0.011f, -0.007f}, t.uv[0] = {0.3f, 0.02f, 0.004f}, t.uv[1] = {-0.2f, 0.003f, 0.03f};
      modules::SpanPacket p;
      p.tri = &t, p.y = 9, p.x0 = 6, p.count = 21;
      for (int k = 0; k < p.count; ++k) p.w[k] = 1.0f / t.inv_w.at(p.x0 + k - t.x_ref, p.y - t.y_ref);
      float out[3][modules::kSpanMax], expected[3][modules::kSpanMax];
      uint16_t cycles[modules::kSpanMax];
      modules::ValueRange range;
      modules::Ops declared, plain_ops;
      C::ops = {};
      modules::sample_span<C>(t, p, map, counted, out, declared, range, cycles);
      modules::sample_span(t, p, map, plain, expected, plain_ops, range, cycles);
      INFO("span: " << test::arithmetic_diff(declared, C::ops));
      CHECK(test::same_arithmetic(declared, C::ops));
      CHECK(declared == plain_ops);
      for (int c = 0; c < 3; ++c) CHECK(std::memcmp(out[c], expected[c], sizeof(float) * size_t(p.count)) == 0);
    }
  }
}
