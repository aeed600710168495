#include <filesystem>

#include "app/commands.hpp"
#include "core/version.hpp"

namespace app {

void SceneOptions::add_to(CLI::App& cmd) {
  cmd.add_option("scene", scene, "scene file (JSON, docs/scene-format.md); the built-in demo if omitted");
  cmd.add_option("--set", overrides, "override a scene field: key=value, e.g. pipeline.normalize.mode=exact")
      ->take_all();
}

core::Scene SceneOptions::load() const {
  return scene.empty() ? core::load_demo_scene(overrides) : core::load_scene(scene, overrides);
}

void describe(core::Frame& frame, const core::Scene& scene, const SceneOptions& options,
              const std::string& renderer) {
  frame.attributes["shadetlm:version"] = core::kVersion;
  frame.attributes["shadetlm:renderer"] = renderer;
  frame.attributes["shadetlm:scene"] = scene.file;
  frame.attributes["shadetlm:config"] = scene.pipeline.resolved().dump();
  frame.attributes["shadetlm:overrides"] = nlohmann::json(options.overrides).dump();
}

void write_frame(const core::Frame& frame, const std::string& exr, const std::string& png) {
  for (const std::string& path : {exr, png}) {
    if (path.empty()) continue;
    const auto dir = std::filesystem::path(path).parent_path();
    if (!dir.empty()) std::filesystem::create_directories(dir);
  }
  if (!exr.empty()) core::write_exr(exr, frame);
  if (!png.empty()) core::write_png_preview(png, frame);
}

}  // namespace app
