#pragma once
// Helpers shared by the tests.
#include <filesystem>
#include <string>

#include <catch2/catch.hpp>

#include "shadetlm/core/frame.hpp"
#include "shadetlm/core/input_error.hpp"
#include "shadetlm/core/scene.hpp"
#include "shadetlm/modules/pipeline/pipeline.hpp"

using namespace shadetlm;  // core::, modules::, reference::

namespace test {

inline std::string source_path(const std::string& relative) {
  return std::string(SHADETLM_SOURCE_DIR) + "/" + relative;
}

// A fresh empty folder for one test.
inline std::filesystem::path temp_dir(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / ("shadetlm-test-" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// True when no channel of the frame holds a NaN.
inline bool no_nan(const core::Frame& f) {
  for (const auto& c : f.channels)
    for (float v : c.values)
      if (v != v) return false;
  return true;
}

// A scene's pipeline settings, resolved against the standard pipeline's declaration.
inline core::Settings settings(const core::Scene& scene) {
  return scene.pipeline.resolve(modules::standard_pipeline().all_settings());
}

// The InputError a scene text raises, or an empty string when it loads.
inline core::InputError scene_error(const std::string& text,
                                    const std::vector<std::string>& overrides = {}) {
  try {
    settings(core::load_scene_text(text, "bad.json", ".", overrides));  // as the program checks it
  } catch (const core::InputError& e) {
    return e;
  }
  FAIL("the scene loaded, but an error was expected");
  throw;  // unreachable
}

}  // namespace test
