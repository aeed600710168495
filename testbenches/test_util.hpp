#pragma once
// Helpers shared by the tests.
#include <filesystem>
#include <string>

#include <catch2/catch.hpp>

#include "core/frame.hpp"
#include "core/input_error.hpp"
#include "core/scene.hpp"

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

// The InputError a scene text raises, or an empty string when it loads.
inline core::InputError scene_error(const std::string& text,
                                    const std::vector<std::string>& overrides = {}) {
  try {
    core::load_scene_text(text, "bad.json", ".", overrides);
  } catch (const core::InputError& e) {
    return e;
  }
  FAIL("the scene loaded, but an error was expected");
  throw;  // unreachable
}

}  // namespace test
