#pragma once
// The `shadetlm` subcommands. Each registers its options on the CLI11 app and returns
// the function that runs it; input errors are thrown as core::InputError and turned
// into exit code 2 by main().
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "shadetlm/core/frame.hpp"
#include "shadetlm/core/scene.hpp"

namespace shadetlm::app {

struct Command {
  CLI::App* cli;            // the subcommand's options
  std::function<int()> run;  // runs it once parsed; returns the exit code
};

Command add_render_command(CLI::App& app);
Command add_bench_command(CLI::App& app);
Command add_reference_command(CLI::App& app);
Command add_compare_command(CLI::App& app);
Command add_precompute_command(CLI::App& app);
Command add_parallax_bench_command(CLI::App& app);
Command add_timing_check_command(CLI::App& app);
// The parallax maps' subcommands of `precompute` (app/parallax_command.cpp): each with
// the function that runs it when it was the one parsed.
void add_map_precompute(CLI::App* precompute, std::vector<std::pair<CLI::App*, std::function<int()>>>& runs);

// Shared by the rendering commands.
struct SceneOptions {
  std::string scene;                 // empty: the built-in demo
  std::vector<std::string> overrides;  // --set key=value
  void add_to(CLI::App& cmd);
  core::Scene load() const;  // and its pipeline settings checked
};
// The scene's pipeline settings, resolved against the standard pipeline's declaration.
core::Settings settings_of(const core::Scene& scene);

// Stamps the header attributes (version, scene, resolved configuration, renderer).
void describe(core::Frame& frame, const core::Scene& scene, const SceneOptions& options,
              const std::string& renderer);
// Writes the frame (EXR), its preview (PNG) and the heat map of its parallax iterations
// (PNG, 0 to heat_max iterations), those named: all or none.
void write_frame(const core::Frame& frame, const std::string& exr, const std::string& png, const std::string& heat = "",
                 float heat_max = 32);

}  // namespace shadetlm::app
