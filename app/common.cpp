#include <algorithm>
#include <filesystem>
#include <thread>
#include <iostream>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "app/commands.hpp"
#include "shadetlm/core/input_error.hpp"
#include "shadetlm/core/nearest.hpp"
#include "shadetlm/core/version.hpp"
#include "shadetlm/modules/pipeline/pipeline.hpp"

namespace shadetlm::app {

void SceneOptions::add_to(CLI::App& cmd) {
  cmd.add_option("scene", scene, "scene file (JSON, docs/scene-format.md); the built-in demo if omitted")
      ->each([this](const std::string&) { given = true; });
  cmd.add_option("--set", overrides, "override a scene field: key=value, e.g. pipeline.normalize.mode=exact")
      ->take_all()
      ->allow_extra_args(false);  // `--set a=1 scene.json`: the scene is no override
}

core::Scene SceneOptions::load() const {
  if (scene.empty() && given) throw core::InputError("", "scene", "an empty path (omit it for the built-in demo)");
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

void add_frame(core::OutputSet& outputs, const core::Frame& frame, const std::string& exr, const std::string& png,
               const std::string& heat, float heat_max) {
  if (!heat.empty() && !frame.find("parallax.iterations"))
    throw core::InputError("--heat-map", heat, "the frame has no parallax.iterations layer (no parallax material)");
  if (!exr.empty()) outputs.write_with(exr, [&](const std::string& tmp) { core::write_exr_to(tmp, exr, frame); });
  if (!png.empty()) outputs.write(png, core::png_preview(frame));
  if (!heat.empty()) outputs.write(heat, core::heat_map_png(frame, "parallax.iterations", heat_max));
}

void write_frame(const core::Frame& frame, const std::string& exr, const std::string& png, const std::string& heat,
                 float heat_max) {
  core::OutputSet outputs;
  add_frame(outputs, frame, exr, png, heat, heat_max);
  outputs.commit();
}

namespace {
// The nearest folder of `path` that exists must take a new entry (the rest is made when
// written): tried, since permissions alone do not tell (root, read-only mounts, /proc).
void probe_writable(const std::string& option, const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path missing = fs::absolute(fs::path(path), ec), folder = missing.parent_path();
  while (!fs::exists(folder, ec) && folder != folder.root_path()) missing = folder, folder = folder.parent_path();
  if (!fs::is_directory(folder, ec)) throw core::InputError(option, path, "its folder " + folder.string() + " is a file");
  int error = 0;
  if (missing.string() != fs::absolute(fs::path(path), ec).string()) {  // a folder to make: try it
    if (::mkdir(missing.c_str(), 0777) == 0) ::rmdir(missing.c_str());
    else error = errno;
  } else {  // a file in an existing folder: an unnamed one (nothing to leave behind if
            // killed), or where the file system has none, the run's own temporary
    int fd = ::open(folder.c_str(), O_TMPFILE | O_WRONLY, 0666);
    if (fd < 0) {
      const std::string probe = core::temporary_path_for(path);
      fd = ::open(probe.c_str(), O_WRONLY | O_CREAT, 0666);
      error = fd < 0 ? errno : 0;
      if (fd >= 0) ::unlink(probe.c_str());
    }
    if (fd >= 0) ::close(fd);
  }
  if (error) throw core::InputError(option, path, std::string("cannot be written: ") + std::strerror(error));
}

bool same_file(const std::string& a, const std::string& b) {
  namespace fs = std::filesystem;
  std::error_code ec1, ec2;
  if (fs::equivalent(a, b, ec1)) return true;  // both exist: links included
  const fs::path ca = fs::weakly_canonical(fs::absolute(a), ec1), cb = fs::weakly_canonical(fs::absolute(b), ec2);
  return !ec1 && !ec2 && ca == cb;
}
}  // namespace

const CLI::Validator kNotEmpty([](std::string& text) { return text.empty() ? std::string("is empty") : std::string(); },
                                "NOT EMPTY");

bool has_extension(const std::string& path, const std::string& extension) {
  if (path.size() < extension.size()) return false;
  std::string end = path.substr(path.size() - extension.size());
  for (char& c : end) c = char(std::tolower(static_cast<unsigned char>(c)));
  return end == extension;
}

// A PNG output names itself .png: a preview written as PNG into p.jpg would mislead
// whatever opens it by its extension.
const CLI::Validator kPngPath(
    [](std::string& text) {
      return has_extension(text, ".png") ? std::string() : "is written as PNG: give a path ending in .png";
    },
    "FILE.png");

// Frames and maps are written as OpenEXR only: a path that names another format (out.png)
// is refused rather than given EXR bytes that a tool choosing by extension misreads.
const CLI::Validator kExrPath(
    [](std::string& text) {
      return has_extension(text, ".exr") ? std::string()
                                         : "is written as OpenEXR: give a path ending in .exr (a PNG: --preview)";
    },
    "FILE.exr");
const CLI::Validator kExrOrPngPath(
    [](std::string& text) {
      return has_extension(text, ".exr") || has_extension(text, ".png")
                 ? std::string()
                 : "is written as OpenEXR (.exr) or PNG (.png): give a path ending in one of them";
    },
    "FILE.exr|FILE.png");

CLI::Validator finite_in(double min, double max) {
  return CLI::Validator(
      [min, max](std::string& text) {
        char* end = nullptr;
        const double x = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0' || !std::isfinite(x))
          return std::string("must be a finite number");
        if (x < min || x > max) return "must lie in [" + CLI::detail::to_string(min) + ", " + CLI::detail::to_string(max) + "]";
        return std::string();
      },
      "FINITE in [" + CLI::detail::to_string(min) + ", " + CLI::detail::to_string(max) + "]");
}

void tidy_help(CLI::App& app) {
  for (CLI::Option* o : app.get_options()) {
    if (o->get_type_size() == 0) continue;  // a flag
    // "TEXT:NOT EMPTY:FILE.exr": the value's type, then each check's description.
    std::string parts = o->get_type_name(), shown;
    for (size_t at = 0, k = 0; at <= parts.size(); ++k) {
      const size_t end = std::min(parts.find(':', at), parts.size());
      std::string part = parts.substr(at, end - at);
      at = end + 1;
      if (k == 0) shown = part;  // TEXT, FLOAT, INT …
      else if (part == "NOT EMPTY") continue;  // (said by the refusal, if it comes)
      else if (part.rfind("FINITE in ", 0) == 0) shown += part.substr(6);  // FLOAT in [a, b]
      else shown = part;  // a file's kind or the choices say more than the type
    }
    for (int k = 0;; ++k) try {
        o->get_validator(k)->description("");
      } catch (const CLI::OptionNotFound&) {
        break;
      }
    o->type_name(shown);
  }
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) tidy_help(*sub);
}

uint64_t replace_nonfinite(core::Frame& frame) {
  uint64_t replaced = 0;
  for (auto& channel : frame.channels)
    for (float& v : channel.values)
      if (channel.name == "Z" ? std::isnan(v) || v == -INFINITY : !std::isfinite(v)) v = 0, ++replaced;
  return replaced;
}

int nonfinite_status(uint64_t replaced, bool allowed) {
  if (replaced == 0) return 0;
  std::cerr << "shadetlm: " << replaced
            << " NaN or infinite values reached the frame and were written as 0 (nonfinite_replaced in --stats)"
            << (allowed ? "" : "; exit status 3 (--allow-nonfinite accepts them)") << "\n";
  return allowed ? 0 : kExitNonfinite;
}

void require_output(const std::string& option, const std::string& path) {
  if (path.empty()) throw core::InputError(option, "", "an empty path: name the file to write");
}

void check_outputs(const std::vector<std::pair<std::string, std::string>>& outputs,
                   const std::vector<std::string>& inputs) {
  namespace fs = std::filesystem;
  for (size_t i = 0; i < outputs.size(); ++i) {
    const auto& [option, path] = outputs[i];
    if (path.empty()) continue;
    for (size_t k = 0; k < i; ++k)
      if (!outputs[k].second.empty() && same_file(path, outputs[k].second))
        throw core::InputError(option, path, "is also the output of " + outputs[k].first);
    for (const std::string& input : inputs)
      if (!input.empty() && same_file(path, input)) throw core::InputError(option, path, "is an input of this run (" + input + ")");
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (fs::is_directory(st)) throw core::InputError(option, path, "is a folder");
    if (fs::exists(st) && !fs::is_regular_file(st))
      throw core::InputError(option, path, "exists and is not a regular file (a FIFO, a device): not replaced");
    probe_writable(option, path);
  }
}

void check_map_cache(const std::string& dir, const std::vector<std::pair<std::string, std::string>>& outputs) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw core::InputError("--map-cache", dir, "exists and is not a folder");
  const fs::path cache = fs::weakly_canonical(fs::absolute(dir), ec);
  for (const auto& [option, path] : outputs) {
    if (path.empty()) continue;
    if (same_file(path, dir)) throw core::InputError(option, path, "is also the --map-cache folder");
    const fs::path out = fs::weakly_canonical(fs::absolute(path), ec);
    const auto [o, c] = std::mismatch(out.begin(), out.end(), cache.begin(), cache.end());
    if (o == out.end())
      throw core::InputError("--map-cache", dir, "lies inside " + path + ", the file of " + option);
  }
}

namespace {
int run_threads = 0;  // set_threads: 0 until set
}

void set_threads(const std::string& text) {
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  char* end = nullptr;
  errno = 0;
  const long n = text.empty() ? long(cores) : std::strtol(text.c_str(), &end, 10);
  if (!text.empty() && (end == text.c_str() || *end != '\0' || errno != 0 || n < 1 || n > 1024))
    throw core::InputError("--threads", text,
                           "expected a count of threads from 1 to 1024 (this machine has " + std::to_string(cores) +
                               " cores)");
  run_threads = int(n);
  core::set_exr_threads(run_threads);
}

int threads() {
  if (run_threads == 0) set_threads("");
  return run_threads;
}

void set_compression(const std::string& name) {
  try {
    core::set_exr_compression(name);
  } catch (const core::InputError& e) {
    if (name.find(':') != std::string::npos) throw;  // (a method with a level: said whole)
    const std::string near = core::nearest_name(name, core::exr_compression_names());
    if (near.empty()) throw;
    throw core::InputError("--compression", name,
                           "unknown: did you mean '" + near + "'? (none, rle, zips, zip, piz, zip:L or zips:L with L 1-9)");
  }
}

}  // namespace shadetlm::app
