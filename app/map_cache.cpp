#include "app/map_cache.hpp"

#include <filesystem>
#include <iostream>
#include <new>
#include <vector>

#include "shadetlm/core/input_error.hpp"
#include "shadetlm/core/parallax_map.hpp"
#include "shadetlm/core/version.hpp"
#include "shadetlm/modules/parallax/parallax_kernel.hpp"

namespace shadetlm::app {

namespace {

// This program as a map's builder: its version, and its file's size and modification
// time, which a rebuild changes even when the version (set when cmake last ran) does
// not. A copy made with its times (cp -p, the Slurm submission's) is the same builder.
std::string builder() {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return core::kVersion;
  const auto size = fs::file_size(self, ec);
  const auto time = fs::last_write_time(self, ec).time_since_epoch().count();
  return std::string(core::kVersion) + " " + std::to_string(size) + " " + std::to_string(time);
}

// "<kind>-<16 hex digits>.exr": FNV-1a over the key's names and values and the builder,
// each with its terminating NUL.
std::string cache_name(const core::MapKey& key) {
  core::Fnv1a h;
  auto mix = [&h](const std::string& text) { h.mix(text.c_str(), text.size() + 1); };
  for (const auto& [name, value] : key) mix(name), mix(value);
  mix(builder());
  return key.at("shadetlm:map") + "-" + h.hex() + ".exr";
}

// What is wrong with the entry at `path` as the map of settings `s` ("" when it reads as
// one). Only what the entry's own contents cause counts; other failures (memory, the
// budget, a file that cannot be opened) go on as they are.
std::string why_unusable(const core::Texture& height, core::ParallaxSettings s, const std::string& path,
                         const std::string& scene_file) {
  s.map_file = path;
  try {
    modules::build_parallax_maps(height, s, scene_file);  // read and checked as the pipeline will
    return "";
  } catch (const core::InputError& e) {
    if (e.file() != path) throw;  // (the scene's or the height map's trouble, not the entry's)
    return e.what();
  }
}

}  // namespace

int use_map_cache(core::Scene& scene, const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (!fs::is_directory(dir)) throw core::InputError("--map-cache", dir, "is not a folder and cannot be made one");
  int built = 0;
  std::vector<bool> used(scene.materials.size());  // maps only for what is drawn, as the pipeline
  for (const core::Object& o : scene.objects) used[size_t(o.material)] = true;
  for (size_t k = 0; k < scene.materials.size(); ++k) {
    if (!used[k]) continue;
    core::Material& m = scene.materials[k];
    core::ParallaxSettings& s = m.parallax;
    const bool reads_map = s.method == core::ParallaxMethod::Distance || s.method == core::ParallaxMethod::Cone;
    if (m.path != core::ShadingPath::Parallax || !reads_map || !s.map_file.empty() || m.height_map < 0) continue;
    const core::Texture& height = scene.textures[size_t(m.height_map)];
    const core::MapKey key = modules::parallax_map_key(core::height_field(height, scene.file, "height_map"), s);
    const std::string path = (fs::path(dir) / cache_name(key)).string();
    bool build = !fs::exists(path);
    if (!build) {
      if (const std::string why = why_unusable(height, s, path, scene.file); !why.empty()) {
        std::cerr << "shadetlm: warning: " << path << ": a map cache entry that cannot be used (" << why
                  << "); built again\n";
        build = true;  // (written over, by a rename: a run reading it meanwhile keeps a whole file)
      }
    }
    if (build) {
      modules::ParallaxMaps maps = modules::build_parallax_maps(height, s, scene.file);
      maps.volume.params["shadetlm:version"] = maps.cone.params["shadetlm:version"] = core::kVersion;
      if (s.method == core::ParallaxMethod::Cone) core::write_cone_map(path, maps.cone);
      else core::write_volume_map(path, maps.volume, key.at("shadetlm:map"));
      ++built;
    }
    s.map_file = path;
  }
  return built;
}

}  // namespace shadetlm::app
