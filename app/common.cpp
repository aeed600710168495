#include <filesystem>

#include "app/commands.hpp"
#include "shadetlm/core/input_error.hpp"
#include "shadetlm/core/version.hpp"
#include "shadetlm/modules/pipeline/pipeline.hpp"

namespace shadetlm::app {

void SceneOptions::add_to(CLI::App& cmd) {
  cmd.add_option("scene", scene, "scene file (JSON, docs/scene-format.md); the built-in demo if omitted");
  cmd.add_option("--set", overrides, "override a scene field: key=value, e.g. pipeline.normalize.mode=exact")
      ->take_all()
      ->allow_extra_args(false);  // `--set a=1 scene.json`: the scene is no override
}

core::Scene SceneOptions::load() const {
  core::Scene s = scene.empty() ? core::load_demo_scene(overrides) : core::load_scene(scene, overrides);
  settings_of(s);  // bad pipeline settings stop every command, not only render
  return s;
}

core::Settings settings_of(const core::Scene& scene) {
  return scene.pipeline.resolve(modules::standard_pipeline().all_settings());
}

void describe(core::Frame& frame, const core::Scene& scene, const SceneOptions& options,
              const std::string& renderer) {
  frame.attributes["shadetlm:version"] = core::kVersion;
  frame.attributes["shadetlm:renderer"] = renderer;
  frame.attributes["shadetlm:scene"] = scene.file;
  // Command-line text need not be UTF-8: replace what is not, rather than fail after
  // the render.
  const auto replace = nlohmann::json::error_handler_t::replace;
  frame.attributes["shadetlm:config"] = settings_of(scene).resolved().dump(-1, ' ', false, replace);
  frame.attributes["shadetlm:overrides"] = nlohmann::json(options.overrides).dump(-1, ' ', false, replace);
}

void write_frame(const core::Frame& frame, const std::string& exr, const std::string& png, const std::string& heat,
                 float heat_max) {
  for (const std::string& path : {exr, png, heat}) {
    if (path.empty()) continue;
    const auto dir = std::filesystem::path(path).parent_path();
    if (!dir.empty()) std::filesystem::create_directories(dir);
  }
  // Both files go to temporaries first: either both appear, or neither does.
  std::vector<std::pair<std::string, std::string>> written;  // (temporary, final)
  try {
    if (!exr.empty()) {
      written.emplace_back(core::temporary_path_for(exr), exr);
      core::write_exr(written.back().first, frame);
    }
    if (!png.empty()) {
      written.emplace_back(core::temporary_path_for(png), png);
      core::write_png_preview(written.back().first, frame);
    }
    if (!heat.empty()) {
      if (!frame.find("parallax.iterations"))
        throw core::InputError("--heat-map", heat, "the frame has no parallax.iterations layer (no parallax material)");
      written.emplace_back(core::temporary_path_for(heat), heat);
      core::write_heat_map_png(written.back().first, frame, "parallax.iterations", heat_max);
    }
  } catch (...) {
    for (const auto& [tmp, path] : written) core::remove_quietly(tmp);
    throw;
  }
  for (const auto& [tmp, path] : written) core::rename_into_place(tmp, path);
}

}  // namespace shadetlm::app
