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

// --help without CLI11's type words: each option of `app` and its subcommands shows what
// it takes (FILE.exr, a choice, FLOAT in [a, b]) rather than "TEXT:NOT EMPTY:FILE.exr".
void tidy_help(CLI::App& app);

// For a command line CLI11 refused: "unknown command 'rendr': did you mean 'render'?" when
// a subcommand or option is a typo away from one it has ("" otherwise).
std::string suggestion(const CLI::App& app, int argc, char** argv);

Command add_render_command(CLI::App& app);
Command add_bench_command(CLI::App& app);
Command add_reference_command(CLI::App& app);
Command add_compare_command(CLI::App& app);
Command add_precompute_command(CLI::App& app);
Command add_parallax_bench_command(CLI::App& app);
Command add_timing_check_command(CLI::App& app);
Command add_cost_command(CLI::App& app);
// The parallax maps' subcommands of `precompute` (app/parallax_command.cpp): each with
// the function that runs it when it was the one parsed.
void add_map_precompute(CLI::App* precompute, std::vector<std::pair<CLI::App*, std::function<int()>>>& runs);

// A numeric option's check: a finite number in [min, max] (CLI::Range lets NaN through,
// and every comparison with it is false). For lists, each element.
CLI::Validator finite_in(double min, double max);
// A path or text option: if given, not empty (an empty one would be taken as not given).
extern const CLI::Validator kNotEmpty;
extern const CLI::Validator kPngPath;  // ends in .png
extern const CLI::Validator kExrPath;  // ends in .exr
extern const CLI::Validator kExrOrPngPath;
// Whether `path` ends in `extension` (".png"), in any case.
bool has_extension(const std::string& path, const std::string& extension);

// Shared by the rendering commands.
struct SceneOptions {
  std::string scene;                 // empty: the built-in demo
  bool given = false;                // a scene argument was given (an empty one is refused)
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
// The same as part of a larger set of outputs (committed by the caller).
void add_frame(core::OutputSet& outputs, const core::Frame& frame, const std::string& exr, const std::string& png,
               const std::string& heat = "", float heat_max = 32);
// Before a run: every output (option, path; "" not asked for) can be written, is no
// folder or special file, and is neither another output nor an input (InputError).
void check_outputs(const std::vector<std::pair<std::string, std::string>>& outputs,
                   const std::vector<std::string>& inputs);
// Before a run: the map cache folder (--map-cache) is a folder or can become one, and no
// output is that folder or a folder holding it (InputError).
void check_map_cache(const std::string& dir, const std::vector<std::pair<std::string, std::string>>& outputs);
// The memory a run will take beyond its scene (app/memory_estimate.cpp): the pipeline's
// frame and buffers and the maps its blocks build, the golden model's image, a trace.
// take_run_memory counts it against the budget, naming the field of the largest part.
struct MemoryNeed {
  uint64_t bytes;
  std::string field;
};
std::vector<MemoryNeed> run_needs(const core::Scene& scene, bool pipeline, bool golden, uint64_t traced_pixels);
void take_run_memory(const core::Scene& scene, bool pipeline, bool golden, uint64_t traced_pixels);

// Non-finite values that reached a frame (replaced by 0 before it was written): said on
// stderr, and the exit status 3 unless the user accepts them (--allow-nonfinite).
// replace_nonfinite does the replacing for a frame made outside the pipeline (Z keeps
// its +inf, the depth of no surface).
uint64_t replace_nonfinite(core::Frame& frame);
int nonfinite_status(uint64_t replaced, bool allowed);
constexpr int kExitNonfinite = 3;

// The top level's --threads (a count from 1 to 1024; "" one per core) and --compression
// (an OpenEXR lossless method): checked (InputError naming the option, with the nearest
// name), then in force for the run: threads() is what the golden model and OpenEXR use.
void set_threads(const std::string& text);
void set_compression(const std::string& name);
int threads();

// An output the command always writes: an empty path is refused.
void require_output(const std::string& option, const std::string& path);

}  // namespace shadetlm::app
