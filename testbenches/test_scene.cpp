// Scene format v1: what loads, and how each kind of bad input is reported.
#include <filesystem>
#include <fstream>

#include "test_util.hpp"

using namespace shadetlm;  // core::, modules::, reference::

using nlohmann::json;

namespace {
json minimal() {
  return json::parse(R"({
    "camera": {"position": [0, 0, 5], "target": [0, 0, 0], "resolution": [64, 48]},
    "lights": [{"type": "directional", "direction": [0, 0, -1]}],
    "materials": {"m": {"diffuse": [0.5, 0.5, 0.5]}},
    "objects": [{"shape": "sphere", "material": "m"}]
  })");
}

// Loads `doc` and returns the error's field and message.
std::pair<std::string, std::string> error_of(const json& doc, std::vector<std::string> sets = {}) {
  core::InputError e = test::scene_error(doc.dump(), sets);
  return {e.field(), e.what()};
}
}  // namespace

TEST_CASE("the minimal scene loads with documented defaults", "[scene]") {
  core::Scene s = core::load_scene_text(minimal().dump(), "min.json", ".");
  CHECK(s.camera.width == 64);
  CHECK(s.camera.height == 48);
  CHECK(s.camera.fov_y_deg == 45);
  CHECK(s.camera.up == glm::dvec3(0, 1, 0));
  CHECK(s.camera.local_viewer);
  REQUIRE(s.lights.size() == 1);
  CHECK(s.lights[0].intensity == 1);
  REQUIRE(s.objects.size() == 1);
  CHECK(s.objects[0].mesh.triangles.size() > 0);
  CHECK(s.materials[s.objects[0].material].path == core::ShadingPath::Phong);
  CHECK(test::settings(s).string("normalize.mode") == "exact");
  CHECK(test::settings(s).number("clock_mhz") == 500);
}

TEST_CASE("every scene in scenes/ and golden/ loads", "[scene]") {
  int count = 0;
  for (const char* dir : {"scenes", "golden"}) {
    for (const auto& entry : std::filesystem::recursive_directory_iterator(test::source_path(dir))) {
      // Scenes are the .json files, except the golden folders' golden.json and stats*.json.
      const std::string file = entry.path().filename().string();
      if (entry.path().extension() != ".json" || file == "golden.json" || file.rfind("stats", 0) == 0) continue;
      INFO(entry.path());
      CHECK_NOTHROW(core::load_scene(entry.path().string()));
      ++count;
    }
  }
  CHECK(count >= 3);
  CHECK_NOTHROW(core::load_demo_scene());
}

TEST_CASE("a full scene reads every section", "[scene]") {
  json doc = minimal();
  doc["ambient"] = {0.1, 0.2, 0.3};
  doc["lights"].push_back({{"type", "point"}, {"position", {1, 2, 3}}, {"color", {1, 0, 0}}, {"intensity", 2}});
  doc["textures"] = {{"c", {{"type", "checker"}, {"size", {16, 8}}, {"cells", {2, 2}}, {"wrap", "clamp"}}},
                     {"h", {{"type", "steps"}, {"levels", 3}}}};
  doc["materials"]["m"]["texture"] = "c";
  doc["materials"]["m"]["height_map"] = "h";
  doc["materials"]["m"]["height_scale"] = 0.05;
  doc["objects"].push_back({{"shape", "plane"}, {"tessellation", {3, 2}},
                            {"transform", {{"translate", {1, 0, 0}}, {"rotate", {0, 90, 0}}, {"scale", 2}}}});
  doc["pipeline"] = {{"normalize", {{"mode", "rsqrt1"}}}, {"normal_interp.mode", "affine"}};
  core::Scene s = core::load_scene_text(doc.dump(), "full.json", ".");
  CHECK(s.ambient == glm::dvec3(0.1, 0.2, 0.3));
  REQUIRE(s.lights.size() == 2);
  CHECK(s.lights[1].type == core::Light::Type::Point);
  CHECK(s.lights[1].radiance() == glm::dvec3(2, 0, 0));
  const core::Material& m = s.materials[s.objects[0].material];
  REQUIRE(m.texture >= 0);
  CHECK(s.textures[m.texture].width == 16);
  CHECK(s.textures[m.texture].wrap == core::Wrap::Clamp);
  CHECK(m.height_map >= 0);
  CHECK(m.height_scale == 0.05);
  CHECK(s.objects[1].mesh.triangles.size() == 12);
  CHECK(s.materials[s.objects[1].material].name == "default");
  // translate · rotate(y, 90°) · scale 2 takes +x to −2z, then shifts by +1 in x.
  glm::dvec4 p = s.objects[1].model * glm::dvec4(1, 0, 0, 1);
  CHECK(p.x == Approx(1.0));
  CHECK(p.z == Approx(-2.0));
  CHECK(test::settings(s).string("normalize.mode") == "rsqrt1");
  CHECK(test::settings(s).string("normal_interp.mode") == "affine");
}

TEST_CASE("overrides (--set) change any field, creating sections as needed", "[scene]") {
  core::Scene s = core::load_scene_text(
      minimal().dump(), "min.json", ".",
      {"lights.0.intensity=2.5", "pipeline.normalize.mode=forward-difference", "camera.resolution=[32,16]",
       "camera.local_viewer=false"});
  CHECK(s.lights[0].intensity == 2.5);
  CHECK(test::settings(s).string("normalize.mode") == "forward-difference");
  CHECK(s.camera.width == 32);
  CHECK(!s.camera.local_viewer);
  CHECK(s.source["lights"][0]["intensity"] == 2.5);
}

TEST_CASE("bad JSON names the line and column", "[scene][bad]") {
  core::InputError e = test::scene_error("{\n  \"camera\": {\n    \"position\": [0, 0 5]\n  }\n}");
  CHECK(e.file() == "bad.json");
  CHECK_THAT(e.field(), Catch::Contains("line 3"));
  CHECK_THAT(e.what(), Catch::Contains("invalid JSON"));
}

TEST_CASE("a missing scene file is reported", "[scene][bad]") {
  try {
    core::load_scene("/nonexistent/scene.json");
    FAIL("no error");
  } catch (const core::InputError& e) {
    CHECK(e.file() == "/nonexistent/scene.json");
    CHECK_THAT(e.what(), Catch::Contains("no such file"));
  }
}

TEST_CASE("a missing mesh or image file names the field", "[scene][bad]") {
  json doc = minimal();
  doc["objects"][0] = {{"shape", "mesh"}, {"file", "nowhere.obj"}};
  CHECK(error_of(doc).first == "objects.0.file");
  doc = minimal();
  doc["textures"] = {{"t", {{"type", "image"}, {"file", "nowhere.png"}}}};
  CHECK(error_of(doc).first == "textures.t.file");
}

TEST_CASE("unknown keys are rejected wherever they are", "[scene][bad]") {
  json doc = minimal();
  doc["camera"]["fovy"] = 30;
  CHECK(error_of(doc).first == "camera.fovy");
  doc = minimal();
  doc["lights"][0]["colour"] = {1, 1, 1};
  CHECK(error_of(doc).first == "lights.0.colour");
  doc = minimal();
  doc["extra"] = 1;
  CHECK(error_of(doc).first == "extra");
  doc = minimal();
  doc["pipeline"] = {{"normalise", {{"mode", "exact"}}}};
  CHECK(error_of(doc).first == "pipeline.normalise.mode");
}

TEST_CASE("a mistyped setting or value is answered with the nearest and not a list of all", "[scene][bad]") {
  auto [field, what] = error_of(minimal(), {"pipeline.normalise.mode=exact"});
  CHECK(field == "pipeline.normalise.mode");
  CHECK_THAT(what, Catch::Contains("did you mean pipeline.normalize.mode?"));
  CHECK(what.size() < 200);  // (it listed every key, 2 KB)
  std::tie(field, what) = error_of(minimal(), {"pipeline.lighting.fifo_dpeth=4"});
  CHECK_THAT(what, Catch::Contains("did you mean pipeline.lighting.fifo_depth?"));
  std::tie(field, what) = error_of(minimal(), {"pipeline.zzzzzzzz=1"});
  CHECK_THAT(what, !Catch::Contains("did you mean") && Catch::Contains("docs/configuration.md"));
  std::tie(field, what) = error_of(minimal(), {"objects.0.shape=spere"});  // a scene's own choice field
  CHECK(field == "objects.0.shape");
  CHECK_THAT(what, Catch::Contains("did you mean \"sphere\"?"));
  json doc = minimal();
  doc["camera"]["fovy"] = 30;  // a scene's own key
  std::tie(field, what) = error_of(doc);
  CHECK(field == "camera.fovy");
  CHECK_THAT(what, Catch::Contains("did you mean fov_y?"));
  std::tie(field, what) = error_of(minimal(), {"pipeline.normalize.mode=exakt"});
  CHECK(field == "pipeline.normalize.mode");
  CHECK_THAT(what, Catch::Contains("did you mean \"exact\"?"));
}

TEST_CASE("normal_map_channels: three axes, each once, with a normal map", "[scene][bad]") {
  json doc = minimal();
  doc["textures"] = {{"nm", {{"type", "checker"}, {"size", {8, 8}}}}};
  doc["materials"]["m"] = {{"path", "bump-tangent"}, {"normal_map", "nm"}};
  auto with = [&](json channels) {
    json d = doc;
    d["materials"]["m"]["normal_map_channels"] = channels;
    return error_of(d);
  };
  CHECK(with({"x", "-y"}).first == "materials.m.normal_map_channels");
  CHECK(with({"x", "w", "z"}).first == "materials.m.normal_map_channels.1");
  CHECK(with({"x", "-x", "z"}).first == "materials.m.normal_map_channels.1");
  CHECK_THAT(with({"x", "-x", "z"}).second, Catch::Contains("two channels"));
  CHECK(with({"x", 1, "z"}).first == "materials.m.normal_map_channels.1");
  json lone = minimal();
  lone["materials"]["m"]["normal_map_channels"] = {"x", "-y", "z"};
  CHECK(error_of(lone).first == "materials.m.normal_map_channels");
}

TEST_CASE("unknown values of choice fields are rejected", "[scene][bad]") {
  json doc = minimal();
  doc["materials"]["m"]["path"] = "phong-fast";
  auto [field, what] = error_of(doc);
  CHECK(field == "materials.m.path");
  CHECK_THAT(what, Catch::Contains("phong"));
  CHECK(error_of(minimal(), {"pipeline.normalize.mode=approximate"}).first == "pipeline.normalize.mode");
  CHECK(error_of(minimal(), {"objects.0.shape=teapot"}).first == "objects.0.shape");
  CHECK(error_of(minimal(), {"lights.0.type=spot"}).first == "lights.0.type");
}

TEST_CASE("wrong types are rejected", "[scene][bad]") {
  CHECK(error_of(minimal(), {"camera.position=\"origin\""}).first == "camera.position");
  CHECK(error_of(minimal(), {"camera.position=[0,\"a\",0]"}).first == "camera.position.1");
  CHECK(error_of(minimal(), {"camera.fov_y=[45]"}).first == "camera.fov_y");
  CHECK(error_of(minimal(), {"camera.resolution=[64.5,48]"}).first == "camera.resolution.0");
  CHECK(error_of(minimal(), {"objects.0.segments=12.5"}).first == "objects.0.segments");
  CHECK(error_of(minimal(), {"camera.local_viewer=1"}).first == "camera.local_viewer");
  CHECK(error_of(minimal(), {"pipeline.clock_mhz=fast"}).first == "pipeline.clock_mhz");
  CHECK(error_of(minimal(), {"materials.m.diffuse=[1,1]"}).first == "materials.m.diffuse");
}

TEST_CASE("NaN and infinite numbers are rejected", "[scene][bad]") {
  // JSON has no NaN or infinity: they can only come as a bare word or an overflowing
  // literal, and both stop the scene with the place named.
  std::string text = minimal().dump(2);
  std::string overflow = text, nan = text;
  overflow.replace(overflow.find("5\n"), 1, "1e999");
  nan.replace(nan.find("5\n"), 1, "NaN");
  core::InputError e = test::scene_error(overflow);
  CHECK(e.file() == "bad.json");
  CHECK_THAT(e.what(), Catch::Contains("1e999"));
  e = test::scene_error(nan);
  CHECK_THAT(e.field(), Catch::Contains("line"));
  CHECK(error_of(minimal(), {"lights.0.intensity=-1e999"}).first == "lights.0.intensity");
  CHECK(error_of(minimal(), {"lights.0.direction=[0,NaN,1]"}).first == "lights.0.direction");
  CHECK(error_of(minimal(), {"lights.0.direction=[0,1e400,1]"}).first == "lights.0.direction");
}

TEST_CASE("a zero or oversized resolution is rejected", "[scene][bad]") {
  CHECK(error_of(minimal(), {"camera.resolution=[0,48]"}).first == "camera.resolution.0");
  CHECK(error_of(minimal(), {"camera.resolution=[64,0]"}).first == "camera.resolution.1");
  CHECK(error_of(minimal(), {"camera.resolution=[64,100000]"}).first == "camera.resolution.1");
}

TEST_CASE("a degenerate camera is rejected", "[scene][bad]") {
  CHECK(error_of(minimal(), {"camera.target=[0,0,5]"}).first == "camera.target");
  CHECK(error_of(minimal(), {"camera.up=[0,0,2]"}).first == "camera.up");
  CHECK(error_of(minimal(), {"camera.up=[0,0,0]"}).first == "camera.up");
  CHECK(error_of(minimal(), {"camera.fov_y=0"}).first == "camera.fov_y");
  CHECK(error_of(minimal(), {"camera.fov_y=180"}).first == "camera.fov_y");
  CHECK(error_of(minimal(), {"camera.near=0"}).first == "camera.near");
  CHECK(error_of(minimal(), {"camera.near=10", "camera.far=5"}).first == "camera.far");
}

TEST_CASE("inconsistent references and values are rejected", "[scene][bad]") {
  CHECK(error_of(minimal(), {"objects.0.material=gold"}).first == "objects.0.material");
  CHECK(error_of(minimal(), {"materials.m.texture=wood"}).first == "materials.m.texture");
  CHECK(error_of(minimal(), {"materials.m.height_scale=0.1"}).first == "materials.m.height_scale");
  CHECK(error_of(minimal(), {"lights.0.direction=[0,0,0]"}).first == "lights.0.direction");
  CHECK(error_of(minimal(), {"materials.m.diffuse=[1,-1,1]"}).first == "materials.m.diffuse");
  CHECK(error_of(minimal(), {"objects.0.transform={\"scale\":[1,0,1]}"}).first == "objects.0.transform.scale");
  json doc = minimal();
  doc["objects"][0] = {{"shape", "torus"}, {"major_radius", 1}, {"minor_radius", 2}};
  CHECK(error_of(doc).first == "objects.0.minor_radius");
  CHECK(error_of(minimal(), {"format=2"}).first == "format");
}

TEST_CASE("bad overrides (--set) are reported", "[scene][bad]") {
  CHECK(error_of(minimal(), {"lights.3.intensity=1"}).first == "lights.3");
  CHECK(error_of(minimal(), {"noequals"}).first == "noequals");
  CHECK(error_of(minimal(), {"camera..near=1"}).first == "camera..near");
  CHECK(error_of(minimal(), {"camera.position.x=1"}).first == "camera.position.x");
  CHECK(error_of(minimal(), {"camera.fov_y.x=1"}).first == "camera.fov_y");  // fov_y became an object
}

TEST_CASE("a key given twice is rejected", "[scene][bad]") {
  std::string text = minimal().dump();
  text.insert(text.find("\"position\""), "\"near\":0.5,\"near\":0.7,");
  core::InputError e = test::scene_error(text);
  CHECK(e.field() == "camera.near");  // its full path, not the bare key
  CHECK_THAT(e.what(), Catch::Contains("twice"));
  json doc = minimal();
  doc["pipeline"] = {{"normalize", {{"mode", "exact"}}}, {"normalize.mode", "rsqrt1"}};
  CHECK(error_of(doc).first == "pipeline.normalize.mode");
}

TEST_CASE("magnitudes that would overflow or underflow are rejected", "[scene][bad]") {
  CHECK(error_of(minimal(), {"objects.0.transform={\"scale\":1e300}"}).first == "objects.0.transform.scale");
  CHECK(error_of(minimal(), {"objects.0.transform={\"scale\":1e-120}"}).first == "objects.0.transform.scale");
  CHECK(error_of(minimal(), {"objects.0.transform={\"translate\":[1e30,0,0]}"}).first ==
        "objects.0.transform.translate");
  CHECK(error_of(minimal(), {"objects.0.radius=1e9"}).first == "objects.0.radius");
  CHECK(error_of(minimal(), {"camera.position=[0,0,1e9]"}).first == "camera.position");
  CHECK(error_of(minimal(), {"camera.resolution=[32768,16]"}).first == "camera.resolution.0");
  CHECK(error_of(minimal(), {"camera.resolution=[16384,16384]"}).first == "camera.resolution");  // 8192² in all
}

TEST_CASE("world space keeps normals unit and fronts in front under any transform", "[scene]") {
  for (const char* t : {R"({"scale": [2, 0.5, 3]})", R"({"scale": [-1, 1, 1]})",
                        R"({"scale": [1, -2, 0.5], "rotate": [30, 60, 10]})"}) {
    INFO(t);
    json doc = minimal();
    doc["objects"][0]["transform"] = json::parse(t);
    const core::Scene s = core::load_scene_text(doc.dump(), "t.json", ".");
    const core::Mesh w = core::to_world(s.objects[0]);
    for (size_t i = 0; i < w.vertex_count(); ++i) {
      CHECK(glm::length(w.normals[i]) == Approx(1.0));
      CHECK(std::abs(glm::dot(w.normals[i], glm::dvec3(w.tangents[i]))) < 1e-12);
      // A sphere around the origin: the world normal points away from the centre.
      CHECK(glm::dot(w.normals[i], w.positions[i]) > 0);
    }
    for (const auto& tri : w.triangles) {
      const glm::dvec3 ng = glm::cross(w.positions[tri.y] - w.positions[tri.x], w.positions[tri.z] - w.positions[tri.x]);
      CHECK(glm::dot(ng, w.normals[tri.x] + w.normals[tri.y] + w.normals[tri.z]) > 0);
    }
  }
}
