// Bump mapping (docs/bump-mapping.md): the precomputation against closed forms, the
// texture unit's filters, the paths against the golden model, and the skipping of the
// bump blocks by materials that do not use them.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "shadetlm/core/bump_map.hpp"
#include "shadetlm/core/compare.hpp"
#include "shadetlm/core/frame.hpp"
#include "shadetlm/sampling/sampler.hpp"
#include "shadetlm/modules/pipeline/pipeline.hpp"
#include "shadetlm/reference/reference.hpp"
#include "systemc_harness.hpp"
#include "test_util.hpp"

using namespace shadetlm;  // core::, modules::, reference::

namespace {

// A height map of W × H texels with h(x, y) = f(u, v) at the texel centres.
template <class F>
core::Texture height_map(int W, int H, core::Wrap wrap, F f) {
  core::Texture t;
  t.name = "test heights";
  t.width = W, t.height = H, t.wrap = wrap;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const double u = (x + 0.5) / W, v = 1 - (y + 0.5) / H;
      t.texels.push_back(glm::vec4(float(f(u, v)), 0, 0, 1));
    }
  return t;
}

// A scene of one object under a directional light, the viewer at infinity.
std::string bump_scene(const std::string& object, const std::string& path, const std::string& extra = "") {
  return R"({"format": 1,
    "camera": {"position": [0, 1.2, 2.6], "target": [0, 0, 0], "resolution": [96, 72], "local_viewer": false},
    "lights": [{"type": "directional", "direction": [-0.5, -0.7, -0.6]}],
    "textures": {"bumps": {"type": "gradient-noise", "size": [128, 128], "cells": 4, "octaves": 2, "seed": 7}},
    "materials": {"phong": {},
                  "bumpy": {"height_map": "bumps", "height_scale": 0.04, "path": ")" +
         path + R"(", "specular": [0.3, 0.3, 0.3], "shininess": 24 )" + extra + R"(}},
    "objects": [)" + object + "]}";
}
const std::string kQuad = R"({"shape": "plane", "size": [2, 2], "material": "bumpy", "transform": {"rotate": [-60, 0, 0]}})";
const std::string kSphere = R"({"shape": "sphere", "radius": 1, "segments": 48, "rings": 24, "material": "bumpy"})";

double psnr_against_golden(const core::Scene& scene) {
  const core::Frame frame = modules::render_loop(scene).frame;
  const core::Frame ref = reference::to_frame(reference::render(scene));
  core::CompareOptions o;
  o.layers = {"RGB"};
  return core::compare_frames(frame, ref, o).layers.at(0).psnr;
}

}  // namespace

TEST_CASE("height derivatives: a ramp has the ramp's slope everywhere, borders included", "[bump]") {
  // h = u on a clamped map: Fu = scale, Fv = 0 (one-sided differences at the borders).
  const core::Texture ramp_u = height_map(16, 8, core::Wrap::Clamp, [](double u, double) { return u; });
  const core::Texture d = core::height_derivatives(ramp_u, 0.5);
  for (const auto& t : d.texels) {
    CHECK(t.r == Approx(0.5).margin(1e-5));
    CHECK(t.g == Approx(0).margin(1e-5));
  }
  // h = v (rows run down, v up): Fv = scale.
  const core::Texture ramp_v = height_map(8, 16, core::Wrap::Clamp, [](double, double v) { return v; });
  for (const auto& t : core::height_derivatives(ramp_v, 2.0).texels) {
    CHECK(t.r == Approx(0).margin(1e-5));
    CHECK(t.g == Approx(2.0).margin(1e-4));
  }
  // A repeating sine: central differences of a period-1 sine, wrapped at the border.
  const double pi2 = 2 * M_PI;
  const core::Texture wave = height_map(64, 64, core::Wrap::Repeat, [&](double u, double) { return std::sin(pi2 * u); });
  const core::Texture dw = core::height_derivatives(wave, 1.0);
  for (int x : {0, 17, 63}) {
    const double u = (x + 0.5) / 64, step = 1.0 / 64;
    const double expected = (std::sin(pi2 * (u + step)) - std::sin(pi2 * (u - step))) / (2 * step);
    CHECK(dw.texels[size_t(x)].r == Approx(expected).epsilon(1e-4));
  }
}

TEST_CASE("perturbed normals: the general form (9) on a square patch equals the square form (10)-(11)", "[bump]") {
  // A plane of side 3 with uv over [0, 1]²: |Pu| = |Pv| = 3 and Pu ⟂ Pv, the paper's
  // square-patch assumption with k = 3, so (9) divided by k² is (10)–(11).
  const core::Texture h = height_map(32, 32, core::Wrap::Repeat, [](double u, double v) {
    return 0.5 + 0.25 * std::sin(2 * M_PI * u) * std::cos(4 * M_PI * v);
  });
  const core::Mesh plane = core::make_plane({3, 3}, {4, 4});
  const core::Texture general = core::surface_normal_map(h, 0.3, plane, core::NormalMapForm::Tangent);
  const core::Texture square = core::square_normal_map(h, 0.3, 3.0);
  const core::Texture object = core::surface_normal_map(h, 0.3, plane, core::NormalMapForm::Object);
  double worst = 0, worst_object = 0;
  for (size_t i = 0; i < square.texels.size(); ++i) {
    worst = std::max(worst, double(glm::length(glm::vec3(general.texels[i]) - glm::vec3(square.texels[i]))));
    // The plane faces +z with u along +x, v along +y: object space is its tangent space.
    worst_object = std::max(worst_object, double(glm::length(glm::vec3(object.texels[i]) - glm::vec3(square.texels[i]))));
    CHECK(glm::length(glm::vec3(square.texels[i])) == Approx(1).epsilon(1e-6));
  }
  CHECK(worst < 1e-6);
  CHECK(worst_object < 1e-6);
  // And the square form is what (10)–(11) say: normalize(−Fu/k, −Fv/k, 1).
  const core::Texture d = core::height_derivatives(h, 0.3);
  const glm::dvec3 expected = glm::normalize(glm::dvec3(-d.texels[37].r / 3.0, -d.texels[37].g / 3.0, 1.0));
  CHECK(glm::length(glm::dvec3(glm::vec3(square.texels[37])) - expected) < 1e-6);
}

TEST_CASE("mip chains: sizes, box averages, renormalization, and a lossless EXR round trip", "[bump]") {
  const core::Texture h = height_map(16, 4, core::Wrap::Repeat, [](double u, double v) { return u * v; });
  const core::Texture n = core::square_normal_map(h, 1.0, 1.0);
  const auto plain = core::mip_levels(n, false), unit = core::mip_levels(n, true);
  REQUIRE(plain.size() == 4);  // 8×2, 4×1, 2×1, 1×1
  CHECK(plain[0].width == 8);
  CHECK(plain[0].height == 2);
  CHECK(plain[3].width == 1);
  CHECK(plain[3].height == 1);
  // Level 1 texel (0, 0) is the mean of the four texels above it.
  const glm::vec4 mean = (n.texels[0] + n.texels[1] + n.texels[16] + n.texels[17]) * 0.25f;
  CHECK(glm::length(plain[0].texels[0] - mean) < 1e-6f);
  for (const auto& level : unit)
    for (const auto& t : level.texels) CHECK(glm::length(glm::vec3(t)) == Approx(1).epsilon(1e-5));

  const auto dir = test::temp_dir("mip-chain");
  const std::string file = (dir / "chain.exr").string();
  core::write_mip_chain(file, n, unit, {{"shadetlm:test", "yes"}});
  const core::Texture back = core::load_texture_file(file);
  REQUIRE(back.mips.size() == unit.size());
  for (size_t i = 0; i < n.texels.size(); ++i) CHECK(glm::vec3(back.texels[i]) == glm::vec3(n.texels[i]));
  for (size_t l = 0; l < unit.size(); ++l)
    for (size_t i = 0; i < unit[l].texels.size(); ++i)
      CHECK(glm::vec3(back.mips[l].texels[i]) == glm::vec3(unit[l].texels[i]));
}

TEST_CASE("height maps the texture unit cannot use are rejected with the file and the field", "[bump]") {
  auto message = [](const core::Texture& t) {
    try {
      core::check_height_map(t, "h.png", "height_map");
    } catch (const core::InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  CHECK(message(height_map(16, 16, core::Wrap::Repeat, [](double, double) { return 0.5; })).empty());
  CHECK(message(height_map(1, 1, core::Wrap::Repeat, [](double, double) { return 0.5; })).empty());   // flat
  CHECK(message(height_map(32, 8, core::Wrap::Repeat, [](double, double) { return 0.5; })).empty());  // not square
  CHECK(message(height_map(12, 16, core::Wrap::Repeat, [](double, double) { return 0.5; })).find("powers of two") !=
        std::string::npos);
  core::Texture nan = height_map(4, 4, core::Wrap::Repeat, [](double, double) { return 0.5; });
  nan.texels[5].r = std::nanf("");
  CHECK(message(nan).find("h.png: height_map: the height map holds NaN") == 0);
  CHECK(message(core::Texture{}).find("empty") != std::string::npos);
  // A 1×1 map is flat: its derivatives are zero and its normal is +z.
  const core::Texture one = height_map(1, 1, core::Wrap::Repeat, [](double, double) { return 0.7; });
  CHECK(glm::vec3(core::square_normal_map(one, 5.0, 1.0).texels[0]) == glm::vec3(0, 0, 1));
}

TEST_CASE("scenes: a bump path needs its map, and names the material when it has none", "[bump]") {
  const auto e = test::scene_error(
      R"({"format": 1, "camera": {"position": [0,0,3], "target": [0,0,0], "resolution": [8,8]},
          "materials": {"rough": {"path": "bump-tangent"}}, "objects": [{"shape": "sphere", "material": "rough"}]})");
  CHECK(std::string(e.what()).find("materials.rough.path") != std::string::npos);
  CHECK(std::string(e.what()).find("\"rough\"") != std::string::npos);
  const auto odd = test::scene_error(bump_scene(kQuad, "bump-tangent"), {"textures.bumps.size=[100,128]"});
  CHECK(std::string(odd.what()).find("materials.bumpy.height_map") != std::string::npos);
  CHECK(std::string(odd.what()).find("powers of two") != std::string::npos);
  const auto k = test::scene_error(bump_scene(kQuad, "bump-tangent", R"(, "square_k": 2)"));
  CHECK(std::string(k.what()).find("square_k") != std::string::npos);
}

TEST_CASE("texture unit: every filter returns a constant texture's value, with fetch and line counts", "[bump]") {
  core::Texture c = height_map(64, 64, core::Wrap::Repeat, [](double, double) { return 0.25; });
  const auto levels = core::mip_levels(c, false);
  modules::MipMap map;
  map.levels.push_back(&c);
  for (const auto& l : levels) map.levels.push_back(&l);
  for (auto f : {modules::Filter::Nearest, modules::Filter::Bilinear, modules::Filter::Trilinear,
                 modules::Filter::Anisotropic}) {
    modules::Sampler s(f, 4);
    modules::Ops ops;
    float out[3];
    // A footprint 6 texels by 1.5 (LOD between levels 1 and 3): anisotropic.
    s.sample(map, 0.3f, 0.6f, 6.0f / 64, 0, 0, 1.5f / 64, out, ops);
    CHECK(out[0] == Approx(0.25f).epsilon(1e-6));
    const uint64_t expected_fetches = f == modules::Filter::Nearest ? 1 : f == modules::Filter::Bilinear ? 4
                                      : f == modules::Filter::Trilinear ? 8 : 4 * 8;
    CHECK(ops.fetch == expected_fetches);
    CHECK(ops.line >= 1);
    CHECK(ops.line <= ops.fetch);
  }
  // LOD: a footprint of 4 texels reads level 2 exactly (bilinear there equals trilinear).
  core::Texture ramp = height_map(64, 64, core::Wrap::Repeat, [](double u, double) { return u; });
  const auto ramp_levels = core::mip_levels(ramp, false);
  modules::MipMap rmap;
  rmap.levels.push_back(&ramp);
  for (const auto& l : ramp_levels) rmap.levels.push_back(&l);
  modules::Sampler tri(modules::Filter::Trilinear, 1);
  modules::Ops ops;
  float out[3];
  tri.sample(rmap, 0.5f, 0.5f, 4.0f / 64, 0, 0, 4.0f / 64, out, ops);
  CHECK(tri.last_lod() == Approx(2.0f));
  CHECK(ops.fetch == 4);  // on a level: one probe
  CHECK(out[0] == Approx(ramp_levels[1].bilinear({0.5, 0.5}).r).epsilon(1e-5));
}

TEST_CASE("the proposed path (bump-tangent, trilinear) is within 1 dB PSNR of the classic path", "[bump][accuracy]") {
  // The paper's gate, against the exact Blinn bump of the golden model, on a flat quad
  // and on a sphere.
  for (const std::string& object : {kQuad, kSphere}) {
    const double classic = psnr_against_golden(core::load_scene_text(bump_scene(object, "bump-classic"), "q", "."));
    const double proposed = psnr_against_golden(core::load_scene_text(bump_scene(object, "bump-tangent"), "q", "."));
    INFO(object << ": classic " << classic << " dB, proposed " << proposed << " dB");
    CHECK(proposed >= classic - 1.0);
    // Both are far from a flat shading of the same surface: the bumps are really there.
    const double phong =
        psnr_against_golden(core::load_scene_text(bump_scene(object, "bump-classic"), "q", ".", {"materials.bumpy.height_scale=0"}));
    CHECK(phong > 90);  // no relief: the paths and the golden model agree closely
    CHECK(classic > 35);
  }
}

TEST_CASE("a material without bump mapping costs the bump blocks nothing", "[bump]") {
  // A Phong-only scene elaborates none of them.
  const modules::RenderResult plain =
      modules::render_loop(core::load_scene_text(bump_scene(kSphere, "bump-tangent"), "s", ".", {"objects.0.material=phong"}));
  for (const auto& b : plain.blocks) {
    CHECK(b.name != "bump_fetch");
    CHECK(b.name != "bump_perturb");
    CHECK(b.name != "normal_mux");
    CHECK(b.name != "vector_interp");  // directional light, viewer at infinity
  }
  // Side by side, a Phong sphere adds nothing to the bump blocks' operations.
  const std::string two = kSphere.substr(0, kSphere.size() - 1) + R"(, "transform": {"translate": [-1.2, 0, 0]}}, )" +
                          R"({"shape": "sphere", "radius": 1, "material": "phong", "transform": {"translate": [1.2, 0, -3]}})";
  const auto ops_of = [](const modules::RenderResult& r, const std::string& block) {
    for (const auto& b : r.blocks)
      if (b.name == block) return b.stats.ops;
    return modules::Ops{};
  };
  const modules::RenderResult mixed = modules::render_loop(core::load_scene_text(bump_scene(two, "bump-tangent"), "m", "."));
  const modules::RenderResult alone = modules::render_loop(
      core::load_scene_text(bump_scene(kSphere.substr(0, kSphere.size() - 1) + R"(, "transform": {"translate": [-1.2, 0, 0]}})",
                                       "bump-tangent"), "a", "."));
  CHECK(mixed.pixels_shaded > alone.pixels_shaded);
  for (const char* block : {"bump_fetch", "normal_mux", "vector_interp"}) {
    INFO(block);
    CHECK(ops_of(mixed, block) == ops_of(alone, block));
  }
  CHECK(ops_of(alone, "bump_fetch").fetch > 0);
}

TEST_CASE("a uv triangle without area neither crashes nor puts NaN into the frame", "[bump]") {
  // A mesh whose uvs are all equal: no tangent frame anywhere.
  const auto dir = test::temp_dir("degenerate-uv");
  {
    std::ofstream obj(dir / "flat-uv.obj");
    obj << "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0.5 0.5\nvn 0 0 1\nf 1/1/1 2/1/1 3/1/1\nf 1/1/1 3/1/1 4/1/1\n";
  }
  for (const char* path : {"bump-classic", "bump-tangent", "bump-square", "bump-object"}) {
    INFO(path);
    std::string text = bump_scene(R"({"shape": "mesh", "file": "flat-uv.obj", "material": "bumpy"})", path);
    const core::Scene scene = core::load_scene_text(text, "d", dir.string());
    const modules::RenderResult r = modules::render_loop(scene);
    CHECK(r.pixels_shaded > 0);
    CHECK(test::no_nan(r.frame));
    CHECK(test::no_nan(reference::to_frame(reference::render(scene))));
  }
}

TEST_CASE("bump paths: SystemC pipeline and plain loop give the same bits", "[bump][systemc]") {
  test::route_systemc_reports_to_failures();
  // Every bump path and Phong in one frame, so that packets of all kinds follow each other.
  std::string objects;
  const char* paths[] = {"bump-classic", "bump-tangent", "bump-square", "bump-object"};
  std::string materials;
  for (int k = 0; k < 4; ++k) {
    objects += std::string(k ? ", " : "") + R"({"shape": "sphere", "radius": 0.45, "material": "m)" + std::to_string(k) +
               R"(", "transform": {"translate": [)" + std::to_string(-1.5 + k) + ", 0, 0]}}";
    materials += std::string(", \"m") + std::to_string(k) + R"(": {"height_map": "bumps", "height_scale": 0.03, "path": ")" +
                 paths[k] + "\"}";
  }
  std::string text = bump_scene(objects + R"(, {"shape": "plane", "size": [6, 3], "material": "phong",
      "transform": {"translate": [0, 0, -1]}})", "bump-tangent");
  text.replace(text.find("\"phong\": {}"), 11, "\"phong\": {}" + materials);
  const core::Scene scene = core::load_scene_text(text, "all", ".", {"pipeline.bump_fetch.filter=anisotropic"});
  const modules::RenderResult sc = modules::render_systemc(scene);
  const modules::RenderResult loop = modules::render_loop(scene);
  for (const auto& c : sc.frame.channels) {
    INFO(c.name);
    CHECK(std::memcmp(c.values.data(), loop.frame.at(c.name).data(), c.values.size() * sizeof(float)) == 0);
  }
  std::vector<std::string> names;
  for (const auto& b : sc.blocks) names.push_back(b.name);
  CHECK(names == std::vector<std::string>{"setup", "raster", "normal_interp", "bump_fetch", "bump_perturb", "normal_mux",
                                          "normalize", "vector_interp", "lighting", "framebuffer"});
  CHECK(sc.total_ops() == loop.total_ops());
}

TEST_CASE("a mirrored parameterization keeps bumps bumps, in every path and in the golden model", "[bump]") {
  // A height ramp h = u on a quad facing +z (viewer and light on +z). With u along +x
  // the surface rises towards +x and its normal leans to −x; with u mirrored (along −x)
  // it leans to +x. Pu × Pv points inwards in the mirrored case: without the sign rule
  // the relief would turn into a dent.
  const auto dir = test::temp_dir("mirrored-uv");
  core::Frame ramp(64, 64);
  auto& r = ramp.add("R");
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) r[size_t(y) * 64 + x] = (x + 0.5f) / 64;
  core::write_exr((dir / "ramp.exr").string(), ramp);
  for (bool mirrored : {false, true}) {
    {
      std::ofstream obj(dir / "quad.obj");
      obj << "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n";
      if (mirrored) obj << "vt 1 0\nvt 0 0\nvt 0 1\nvt 1 1\n";
      else obj << "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n";
      obj << "vn 0 0 1\nf 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\n";
    }
    for (const char* path : {"bump-classic", "bump-tangent", "bump-square", "bump-object"}) {
      INFO((mirrored ? "mirrored, " : "plain, ") << path);
      const std::string text = R"({"format": 1,
        "camera": {"position": [0, 0, 3], "target": [0, 0, 0], "resolution": [32, 32], "local_viewer": false},
        "lights": [{"type": "directional", "direction": [0, 0, -1]}],
        "textures": {"ramp": {"type": "image", "file": "ramp.exr", "wrap": "clamp"}},
        "materials": {"m": {"height_map": "ramp", "height_scale": 0.2, "path": ")" + std::string(path) +
                               R"(" )" + (std::string(path) == "bump-square" ? R"(, "square_k": 2)" : "") + R"(}},
        "objects": [{"shape": "mesh", "file": "quad.obj", "material": "m"}]})";
      const core::Scene scene = core::load_scene_text(text, "mirror", dir.string());
      const reference::Image golden = reference::render(scene);
      const size_t centre = golden.index(16, 16);
      // The golden model's perturbed normal in world space: classic's N layer; lit colour for all.
      const core::Frame frame = modules::render_loop(scene).frame;
      if (std::string(path) == "bump-classic") {
        CHECK((mirrored ? golden.normal[centre].x > 0.05 : golden.normal[centre].x < -0.05));
        CHECK((mirrored ? frame.at("N.X")[centre] > 0.05f : frame.at("N.X")[centre] < -0.05f));
      }
      // Every path agrees with the golden model, mirrored or not.
      core::CompareOptions o;
      o.layers = {"RGB"};
      CHECK(core::compare_frames(frame, reference::to_frame(golden), o).layers.at(0).psnr > 40);
    }
  }
}

TEST_CASE("normal maps stored at 8, 10, 16 bits: the error grows as the bits fall, float is the floor", "[bump][accuracy]") {
  // The golden model's truth stays the height field; only the map's storage changes.
  double psnr[4];
  const char* stored[4] = {"float", "unorm16", "unorm10", "unorm8"};
  for (int k = 0; k < 4; ++k)
    psnr[k] = psnr_against_golden(core::load_scene_text(bump_scene(kSphere, "bump-tangent"), "q", ".",
                                                        {std::string("pipeline.bump_fetch.stored=") + stored[k]}));
  INFO("PSNR float " << psnr[0] << ", unorm16 " << psnr[1] << ", unorm10 " << psnr[2] << ", unorm8 " << psnr[3]);
  CHECK(psnr[1] > psnr[2]);
  CHECK(psnr[2] > psnr[3]);
  // 16 bits (a step of 3e-5) is below the filter's own error: within 0.1 dB of float.
  CHECK(std::abs(psnr[1] - psnr[0]) < 0.1);
}

// A 2×2 normal map PNG (N + 1) / 2 of the given bytes, in a fresh folder; a scene over it.
namespace {
std::filesystem::path normal_map_png(const std::string& name, const unsigned char (&bytes)[4][3]) {
  const auto dir = test::temp_dir(name);
  std::vector<unsigned char> rgb(bytes[0], bytes[0] + 12);
  std::ofstream((dir / "nm.png").string(), std::ios::binary) << core::encode_png(2, 2, rgb);
  return dir;
}
core::Scene normal_map_scene(const std::filesystem::path& dir, const std::string& channels, int size = 8) {
  const std::string text = R"({"format": 1, "camera": {"position": [0, 0, 3], "target": [0, 0, 0], "resolution": [)" +
                           std::to_string(size) + "," + std::to_string(size) + R"(]},
    "lights": [{"type": "directional", "direction": [-0.5, -0.6, -1]}],
    "textures": {"nm": {"type": "image", "file": "nm.png", "colorspace": "linear"}},
    "materials": {"m": {"path": "bump-tangent", "normal_map": "nm")" +
                           (channels.empty() ? "" : ", \"normal_map_channels\": " + channels) + R"(}},
    "objects": [{"shape": "sphere", "material": "m"}]})";
  return core::load_scene_text(text, "nm.json", dir.string());
}
const core::Texture& normal_map_of(const core::Scene& scene) {
  return scene.textures[size_t(scene.materials[size_t(scene.objects[0].material)].normal_map)];
}
}  // namespace

TEST_CASE("an 8-bit normal map file is read as (N + 1) / 2 and decoded as 2x - 1", "[bump]") {
  // A 2×2 PNG whose texels hold the bytes of N = (0, 0, 1), (1, 0, 0), (0, -1, 0), (0.6, 0, 0.8).
  const unsigned char bytes[4][3] = {{128, 128, 255}, {255, 128, 128}, {128, 0, 128}, {204, 128, 230}};
  const auto dir = normal_map_png("nm-8bit", bytes);
  const std::string text = R"({"format": 1, "camera": {"position": [0, 0, 3], "target": [0, 0, 0], "resolution": [8, 8]},
    "textures": {"nm": {"type": "image", "file": "nm.png", "colorspace": "srgb"}},
    "materials": {"m": {"path": "bump-tangent", "normal_map": "nm"}},
    "objects": [{"shape": "sphere", "material": "m"}]})";
  const core::Scene scene = core::load_scene_text(text, "nm.json", dir.string());
  const auto m = std::find_if(scene.materials.begin(), scene.materials.end(), [](const auto& x) { return x.name == "m"; });
  REQUIRE(m != scene.materials.end());
  const core::Texture& map = scene.textures[size_t(m->normal_map)];
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) CHECK(map.texels[size_t(i)][k] == Approx(bytes[i][k] / 255.0 * 2 - 1).margin(1e-6));
  std::filesystem::remove_all(dir);
}

TEST_CASE("normal_map_channels: a map's green up or down, an object-space map's axes, read as declared", "[bump]") {
  // N = (0, 0, 1), (1, 0, 0), (0, -1, 0), (0.6, 0, 0.8) as stored bytes.
  const unsigned char bytes[4][3] = {{128, 128, 255}, {255, 128, 128}, {128, 0, 128}, {204, 128, 230}};
  const auto dir = normal_map_png("nm-channels", bytes);
  auto stored = [&](int i, int c) { return bytes[i][c] / 255.0 * 2 - 1; };
  // Green down (DirectX): texel 2's stored -1 in green is +1 on y.
  const core::Scene down_scene = normal_map_scene(dir, R"(["x", "-y", "z"])");
  const core::Texture& down = normal_map_of(down_scene);
  CHECK(down.texels[2].y == Approx(1).margin(1e-6));
  // A Z-up tool's object-space map, the mesh read Y-up as (x, y, z) = (X, Z, -Y): R holds
  // x, G (the tool's Y) -z, B (its Z) y.
  const core::Scene z_up_scene = normal_map_scene(dir, R"(["x", "-z", "y"])");
  const core::Texture& z_up = normal_map_of(z_up_scene);
  CHECK(z_up.texels[2].z == Approx(1).margin(1e-6));   // the tool's -Y is the model's +z
  CHECK(z_up.texels[0].y == Approx(1).margin(0.01));   // the tool's up (B = 1) is the model's up
  for (int i = 0; i < 4; ++i) {
    CHECK(down.texels[size_t(i)].x == Approx(stored(i, 0)).margin(1e-6));
    CHECK(down.texels[size_t(i)].y == Approx(-stored(i, 1)).margin(1e-6));
    CHECK(down.texels[size_t(i)].z == Approx(stored(i, 2)).margin(1e-6));
    CHECK(z_up.texels[size_t(i)].x == Approx(stored(i, 0)).margin(1e-6));
    CHECK(z_up.texels[size_t(i)].z == Approx(-stored(i, 1)).margin(1e-6));
    CHECK(z_up.texels[size_t(i)].y == Approx(stored(i, 2)).margin(1e-6));
  }
  // The default, and the default spelled out, read R, G, B as x, y, z.
  const core::Scene plain_scene = normal_map_scene(dir, ""), spelled_scene = normal_map_scene(dir, R"(["+x", "y", "z"])");
  const core::Texture &plain = normal_map_of(plain_scene), &spelled = normal_map_of(spelled_scene);
  for (int i = 0; i < 4; ++i) CHECK(glm::vec3(plain.texels[size_t(i)]) == glm::vec3(spelled.texels[size_t(i)]));
  std::filesystem::remove_all(dir);
}

TEST_CASE("a green-down normal map declared so renders as its green-up twin", "[bump]") {
  // One map written twice: green up, and with its green bytes inverted (255 - g).
  const unsigned char up[4][3] = {{128, 170, 230}, {90, 140, 240}, {150, 60, 220}, {128, 128, 255}};
  unsigned char down[4][3];
  for (int i = 0; i < 4; ++i) down[i][0] = up[i][0], down[i][1] = uint8_t(255 - up[i][1]), down[i][2] = up[i][2];
  const auto up_dir = normal_map_png("nm-up", up), down_dir = normal_map_png("nm-down", down);
  const core::Frame a = modules::render_loop(normal_map_scene(up_dir, "", 48)).frame;
  const core::Frame b = modules::render_loop(normal_map_scene(down_dir, R"(["x", "-y", "z"])", 48)).frame;
  const core::Frame wrong = modules::render_loop(normal_map_scene(down_dir, "", 48)).frame;
  core::CompareOptions o;
  o.layers = {"RGB"};
  // (2(255 - g)/255 - 1 is -(2g/255 - 1) up to float rounding: equal to 1e-6, not bit for bit.)
  CHECK(core::compare_frames(a, b, o).layers.at(0).max_abs < 1e-5);
  CHECK(core::compare_frames(a, wrong, o).layers.at(0).max_abs > 1e-2);  // the convention matters here
  std::filesystem::remove_all(up_dir), std::filesystem::remove_all(down_dir);
}

TEST_CASE("Phong's H interpolated as Fig. 1 draws it: fewer operations a pixel, less exact near a point light", "[bump][accuracy]") {
  struct Run {
    double psnr;
    modules::Ops vector_ops;
  };
  auto run = [](const std::string& h) {
    const core::Scene scene =
        core::load_scene(test::source_path("golden/point-light/scene.json"), {"pipeline.vector_interp.h=" + h});
    const modules::RenderResult r = modules::render_loop(scene);
    core::CompareOptions o;
    o.layers = {"RGB"};
    const double psnr = core::compare_frames(r.frame, reference::to_frame(reference::render(scene)), o).layers.at(0).psnr;
    for (const auto& b : r.blocks)
      if (b.name == "vector_interp") return Run{psnr, b.stats.ops};
    FAIL("no vector_interp block");
    return Run{};
  };
  const Run pixel = run("pixel"), interpolated = run("interpolated");
  INFO("PSNR per-pixel H " << pixel.psnr << ", interpolated H " << interpolated.psnr);
  // Per pixel: V's interpolation and normalization and L̂ + V̂ (6 mul, 5 add, a sqrt, a
  // div) drop out; H's interpolation (3 mul, 3 add) comes in.
  CHECK(interpolated.vector_ops.mul < pixel.vector_ops.mul);
  CHECK(interpolated.vector_ops.sqrt < pixel.vector_ops.sqrt);
  // H is not affine over a triangle: interpolating it costs accuracy near the light
  // (measured 37.3 against 131.5 dB), yet stays a picture of the highlight.
  CHECK(interpolated.psnr < pixel.psnr - 20);
  CHECK(interpolated.psnr > 30);
}
