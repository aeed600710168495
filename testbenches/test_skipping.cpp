// Skipping what a scene does not need (docs/pipeline.md): blocks not elaborated, packets
// that bypass, the early depth test before the expensive blocks, no packets where
// nothing is covered.
#include "shadetlm/modules/pipeline/pipeline.hpp"
#include "test_util.hpp"

using namespace shadetlm;  // core::, modules::, reference::

namespace {

// `layers` quads of the same size stacked along the view axis, listed front to back or
// back to front (the drawing order): overdraw `layers` where they overlap.
std::string stacked_quads(int layers, bool front_to_back) {
  std::string objects;
  for (int k = 0; k < layers; ++k) {
    const int depth = front_to_back ? k : layers - 1 - k;
    objects += std::string(k ? ", " : "") + R"({"shape": "plane", "size": [2, 2], "transform": {"translate": [0, 0, )" +
               std::to_string(-0.1 * depth) + "]}}";
  }
  return R"({"format": 1, "camera": {"position": [0, 0, 3], "target": [0, 0, 0], "resolution": [64, 64],
             "local_viewer": false},
             "lights": [{"type": "directional", "direction": [0, 0, -1]}], "objects": [)" + objects + "]}";
}

const modules::BlockReport* block(const modules::RenderResult& r, const std::string& name) {
  for (const auto& b : r.blocks)
    if (b.name == name) return &b;
  return nullptr;
}

}  // namespace

TEST_CASE("early depth test: front to back, shading work stays flat as overdraw grows; back to front it grows",
          "[skipping]") {
  uint64_t front_one = 0;
  for (int layers : {1, 4, 16}) {
    INFO(layers << " layers");
    const auto front = modules::render_loop(core::load_scene_text(stacked_quads(layers, true), "f", "."));
    const auto back = modules::render_loop(core::load_scene_text(stacked_quads(layers, false), "b", "."));
    if (layers == 1) front_one = front.pixels_shaded;
    // Front to back: every hidden fragment is rejected by the raster's depth test, before
    // normal_interp … lighting; the lighting block shades each pixel once.
    CHECK(front.pixels_shaded == front_one);
    CHECK(block(front, "lighting")->stats.ops == block(modules::render_loop(core::load_scene_text(
                                                              stacked_quads(1, true), "f", ".")), "lighting")->stats.ops);
    CHECK(front.pixels_shaded + front.pixels_hidden == front.pixels_walked);
    // Back to front: each nearer quad passes the test and is shaded again — every
    // fragment walked (the farther quads are a little smaller on screen).
    CHECK(back.pixels_hidden == 0);
    CHECK(back.pixels_shaded == front.pixels_walked);
    CHECK(back.pixels_shaded >= uint64_t(layers) * front_one * 9 / 10);
    // The same frame either way.
    CHECK(front.frame.at("R") == back.frame.at("R"));
  }
}

TEST_CASE("regions with nothing covered generate no packets", "[skipping]") {
  // A small sphere in a large frame: the raster walks its spans only.
  const auto r = modules::render_loop(core::load_scene_text(R"({"format": 1,
      "camera": {"position": [0, 0, 20], "target": [0, 0, 0], "resolution": [512, 512]},
      "lights": [{"type": "directional", "direction": [0, 0, -1]}],
      "objects": [{"shape": "sphere", "radius": 1}]})", "s", "."));
  CHECK(r.pixels_shaded > 1000);
  CHECK(r.pixels_shaded < 512 * 512 / 20);
  CHECK(r.pixels_walked <= r.pixels_shaded + r.pixels_hidden);
  // Packets: one per visible run of a row of a triangle, never one for an empty row.
  const auto* lighting = block(r, "lighting");
  REQUIRE(lighting);
  CHECK(lighting->stats.ops.lut == r.pixels_shaded);  // the specular power once per shaded pixel
}

TEST_CASE("the stats list the blocks elaborated; elaborate = all adds the others, which cost Phong nothing",
          "[skipping]") {
  const std::string phong = stacked_quads(1, true);
  const auto needed = modules::render_loop(core::load_scene_text(phong, "p", "."));
  const auto all = modules::render_loop(core::load_scene_text(phong, "p", ".", {"pipeline.elaborate=all"}));
  std::vector<std::string> names;
  for (const auto& n : needed.stats_json()["elaborated"]) names.push_back(n.get<std::string>());
  CHECK(names == std::vector<std::string>{"setup", "raster", "normal_interp", "normalize", "lighting", "framebuffer"});
  CHECK(all.stats_json()["elaborated"].size() == modules::standard_pipeline().block_names().size());
  // The extra blocks let Phong packets pass: no operations, the same frame.
  for (const char* b : {"bump_fetch", "bump_perturb", "vector_interp", "texture_fetch", "texel_project"}) {
    INFO(b);
    REQUIRE(block(all, b));
    CHECK(block(all, b)->stats.ops.total() == 0);
  }
  CHECK(all.frame.at("R") == needed.frame.at("R"));
  CHECK(all.total_ops() == needed.total_ops());
}
