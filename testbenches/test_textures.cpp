// Textures: the addressing convention, the procedural generators, image files.
#include <set>

#include <stb_image_write.h>

#include "shadetlm/core/frame.hpp"
#include "shadetlm/core/texture.hpp"
#include "test_util.hpp"

using namespace shadetlm;  // core::, modules::, reference::

namespace {
core::Texture ramp(int w, int h, core::Wrap wrap) {
  core::Texture t;
  t.width = w;
  t.height = h;
  t.wrap = wrap;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) t.texels.push_back(glm::vec4(float(x), float(y), 0, 1));
  return t;
}
}  // namespace

TEST_CASE("a texel centre reads back that texel, and v = 1 is the top row", "[texture]") {
  const core::Texture t = ramp(8, 4, core::Wrap::Repeat);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x) {
      glm::dvec4 c = t.bilinear({(x + 0.5) / 8, 1 - (y + 0.5) / 4});
      CHECK(c.x == Approx(x).margin(1e-12));
      CHECK(c.y == Approx(y).margin(1e-12));
    }
  // Half-way between texels 2 and 3 of row 1.
  CHECK(t.bilinear({3.0 / 8, 1 - 1.5 / 4}).x == Approx(2.5));
}

TEST_CASE("repeat wraps and clamp clamps at the borders", "[texture]") {
  const core::Texture rep = ramp(8, 4, core::Wrap::Repeat), cl = ramp(8, 4, core::Wrap::Clamp);
  CHECK(rep.texel(-1, 0).x == 7);
  CHECK(rep.texel(8, 5).x == 0);
  CHECK(rep.texel(8, 5).y == 1);
  CHECK(cl.texel(-3, 9).x == 0);
  CHECK(cl.texel(-3, 9).y == 3);
  // At u = 0 the bilinear footprint straddles the left border.
  CHECK(rep.bilinear({0.0, 1 - 0.5 / 4}).x == Approx(3.5));  // (7 + 0) / 2
  CHECK(cl.bilinear({0.0, 1 - 0.5 / 4}).x == Approx(0.0));
}

TEST_CASE("procedural textures have their documented ranges and structure", "[texture]") {
  core::ProceduralParams p;
  p.size = {64, 64};
  p.cells = {4, 4};
  p.octaves = 3;
  auto range_ok = [](const core::Texture& t) {
    for (const auto& c : t.texels)
      if (!(c.r >= 0 && c.r <= 1)) return false;
    return true;
  };
  const core::Texture checker = core::make_checker(p);
  CHECK(checker.texel(0, 0).r != checker.texel(16, 0).r);
  CHECK(checker.texel(0, 0).r == checker.texel(16, 16).r);
  for (auto make : {core::make_bricks, core::make_tiles, core::make_value_noise, core::make_gradient_noise,
                    core::make_ridges, core::make_steps})
    CHECK(range_ok(make(p)));
  p.levels = 5;
  std::set<float> levels;
  for (const auto& c : core::make_steps(p).texels) levels.insert(c.r);
  CHECK(levels.size() >= 3);
  CHECK(levels.size() <= 5);
  const core::Texture bricks = core::make_bricks(p);
  std::set<float> values;
  for (const auto& c : bricks.texels) values.insert(c.r);
  CHECK(values == std::set<float>{0.0f, 1.0f});  // sharp: brick or mortar, nothing between
}

TEST_CASE("noise textures tile seamlessly and depend on the seed", "[texture]") {
  core::ProceduralParams p;
  p.size = {128, 128};
  p.cells = {4, 4};
  p.octaves = 2;
  for (auto make : {core::make_value_noise, core::make_gradient_noise}) {
    const core::Texture t = make(p);
    // The jump across the wrap-around seam is no larger than between neighbours inside.
    double inside = 0, seam = 0;
    for (int y = 0; y < 128; ++y) {
      for (int x = 0; x + 1 < 128; ++x) inside = std::max(inside, std::abs(t.texel(x + 1, y).r - t.texel(x, y).r));
      seam = std::max(seam, std::abs(t.texel(0, y).r - t.texel(127, y).r));
    }
    CHECK(seam <= inside * 1.5);
    p.seed = 2;
    const core::Texture other = make(p);
    p.seed = 1;
    CHECK(other.texels != t.texels);
    CHECK(make(p).texels == t.texels);
  }
}

TEST_CASE("PNG textures load through stb and decode from sRGB", "[texture]") {
  const auto dir = test::temp_dir("png");
  const std::string path = (dir / "t.png").string();
  const unsigned char px[2 * 1 * 3] = {255, 128, 0, 0, 0, 255};
  REQUIRE(stbi_write_png(path.c_str(), 2, 1, 3, px, 6));
  const core::Texture t = core::load_texture_file(path);
  CHECK(t.width == 2);
  CHECK(t.srgb);
  CHECK(t.texel(0, 0).r == Approx(1.0));
  CHECK(t.texel(0, 0).g == Approx(128 / 255.0).margin(1e-4));
  CHECK(t.texel(1, 0).b == Approx(1.0));
  CHECK(t.texel(0, 0).a == Approx(1.0));
  const core::Texture lin = core::decode_srgb(t);
  CHECK(lin.texel(0, 0).g == Approx(core::srgb_to_linear(128 / 255.0)).margin(1e-6));
  CHECK(core::linear_to_srgb(core::srgb_to_linear(0.3)) == Approx(0.3));
}

TEST_CASE("an unreadable image names the file", "[texture][bad]") {
  const auto dir = test::temp_dir("png-bad");
  const std::string path = (dir / "t.png").string();
  std::FILE* f = std::fopen(path.c_str(), "w");
  std::fputs("not a png", f);
  std::fclose(f);
  try {
    core::load_texture_file(path);
    FAIL("no error");
  } catch (const core::InputError& e) {
    CHECK(e.file() == path);
  }
  CHECK_THROWS_AS(core::load_texture_file((dir / "t.bmp").string()), core::InputError);
}

TEST_CASE("a grey EXR (channel Y) reads as equal R, G and B", "[texture]") {
  const auto dir = test::temp_dir("grey-exr");
  core::Frame grey(4, 2);
  auto& y = grey.add("Y");
  for (size_t i = 0; i < y.size(); ++i) y[i] = 0.1f * float(i);
  core::write_exr((dir / "grey.exr").string(), grey);
  const core::Texture t = core::load_texture_file((dir / "grey.exr").string());
  REQUIRE(t.texels.size() == 8);
  for (size_t i = 0; i < 8; ++i) {
    CHECK(t.texels[i].r == 0.1f * float(i));
    CHECK(t.texels[i].g == t.texels[i].r);
    CHECK(t.texels[i].b == t.texels[i].r);
    CHECK(t.texels[i].a == 1.0f);
  }
}
