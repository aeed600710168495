// The documentation keeps up with the code: every pipeline setting is documented, and
// the units table gives the timing the pipeline builds.
#include <fstream>
#include <regex>
#include <sstream>

#include "shadetlm/modules/pipeline/pipeline.hpp"

#include "test_util.hpp"

using namespace shadetlm;  // core::, modules::, reference::

TEST_CASE("every pipeline setting appears in docs/configuration.md", "[docs]") {
  std::ifstream in(test::source_path("docs/configuration.md"));
  REQUIRE(in);
  std::stringstream ss;
  ss << in.rdbuf();
  for (const auto& s : modules::standard_pipeline().all_settings()) {
    INFO(s.key);
    CHECK_THAT(ss.str(), Catch::Contains("`pipeline." + s.key + "`"));
  }
}

TEST_CASE("the normalize units table of docs/configuration.md is the pipeline's", "[docs]") {
  // Each row "| `mode` | units | latency, II |" against the timing the pipeline builds.
  std::ifstream in(test::source_path("docs/configuration.md"));
  REQUIRE(in);
  std::string line;
  int rows = 0;
  while (std::getline(in, line)) {
    std::smatch m;
    if (!std::regex_match(line, m, std::regex(R"(\| `([a-z0-9-]+)` \| [^|]+ \| (\d+), (\d+) \|)"))) continue;
    INFO(line);
    core::Scene scene = core::load_scene(test::source_path("golden/sphere/scene.json"));
    scene.pipeline = core::PipelineConfig::from_json(nlohmann::json{{"normalize", {{"mode", m[1].str()}}}}, "test");
    modules::Pipeline pipeline(scene);
    for (const auto& b : pipeline.blocks())
      if (b.name == "normalize") {
        CHECK(b.timing.latency == std::stoull(m[2].str()));
        CHECK(b.timing.ii == std::stoull(m[3].str()));
        ++rows;
      }
  }
  CHECK(rows == 5);
}
