// The documentation keeps up with the code: every pipeline setting is documented.
#include <fstream>
#include <sstream>

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
