#pragma once
// Helpers shared by the tests.
#include <filesystem>
#include <sstream>
#include <string>

#include <catch2/catch.hpp>

#include "shadetlm/core/frame.hpp"
#include "shadetlm/core/input_error.hpp"
#include "shadetlm/core/scene.hpp"
#include "shadetlm/modules/pipeline/pipeline.hpp"
#include "shadetlm/numeric/ops.hpp"

using namespace shadetlm;  // core::, modules::, reference::

namespace test {

// Whether a declared operation tally's arithmetic is what a counting type counted
// (fetches and memory lines are a block's own tally, checked apart).
inline bool same_arithmetic(const modules::Ops& declared, const modules::Ops& counted) {
  return declared.add == counted.add && declared.mul == counted.mul && declared.div == counted.div &&
         declared.sqrt == counted.sqrt && declared.rsqrt == counted.rsqrt && declared.lut == counted.lut;
}

// "declared-counted add 0 mul 2 …", for a failed same_arithmetic's message.
inline std::string arithmetic_diff(const modules::Ops& declared, const modules::Ops& counted) {
  auto d = [](uint64_t a, uint64_t b) { return int64_t(a - b); };
  std::ostringstream s;
  s << "declared-counted add " << d(declared.add, counted.add) << " mul " << d(declared.mul, counted.mul)
    << " div " << d(declared.div, counted.div) << " sqrt " << d(declared.sqrt, counted.sqrt) << " rsqrt "
    << d(declared.rsqrt, counted.rsqrt) << " lut " << d(declared.lut, counted.lut);
  return s.str();
}

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
