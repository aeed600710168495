// shadetlm precompute normalmap HEIGHT -o ntex.exr [--scale S] [--k K]
//                                      [--surface plane|sphere|torus|MESH] [--form ...]
// Precomputed textures for the pipeline's texture units (docs/bump-mapping.md): the
// bump-mapping paper's texture of perturbed normals, with its full mip chain, as one
// tiled mip-mapped EXR that a scene names as a material's normal_map. The parallax maps
// (distancemap, refinedmap, conemap) are in app/parallax_command.cpp.
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>

#include "app/commands.hpp"
#include "app/progress.hpp"
#include "shadetlm/core/compare.hpp"
#include "shadetlm/core/bump_map.hpp"
#include "shadetlm/core/frame.hpp"
#include "shadetlm/core/input_error.hpp"
#include "shadetlm/core/mesh_io.hpp"
#include "shadetlm/core/version.hpp"

namespace shadetlm::app {

namespace {

core::Mesh surface_mesh(const std::string& surface) {
  // The primitives as a scene's defaults make them (docs/scene-format.md).
  if (surface == "plane") return core::make_plane({2, 2}, {1, 1});
  if (surface == "sphere") return core::make_sphere(1, 48, 24);
  if (surface == "torus") return core::make_torus(1, 0.35, 48, 24);
  if (!std::filesystem::is_regular_file(surface))
    throw core::InputError(surface, "--surface", "not plane, sphere, torus or a mesh file");
  return core::load_mesh_file(surface);
}

}  // namespace

namespace {
// The finest level as an 8-bit PNG, as normal maps are stored: (N + 1) / 2 (core::encode_unorm).
std::string normal_map_png(const core::Texture& map) {
  std::vector<unsigned char> rgb(size_t(map.width) * size_t(map.height) * 3);
  for (size_t i = 0; i < map.texels.size(); ++i)
    for (int k = 0; k < 3; ++k) rgb[i * 3 + size_t(k)] = static_cast<unsigned char>(core::encode_unorm(map.texels[i][k], 8));
  return core::encode_png(map.width, map.height, rgb);
}
}  // namespace

Command add_precompute_command(CLI::App& app) {
  struct Options {
    std::string height, output = "out/normalmap.exr", surface, form, wrap = "repeat";
    double scale = 1, k = 1;
    bool keep_mip_lengths = false;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("precompute", "precompute textures for the texture units");
  cmd->require_subcommand(1);
  CLI::App* nm = cmd->add_subcommand("normalmap", "texture of perturbed normals from a height map (bump mapping)");
  nm->add_option("height", opt->height, "height map image (first channel; PNG or EXR, power-of-two sides)")->required();
  nm->add_option("-o,--output", opt->output,
                 "EXR to write (tiled, mip-mapped, float), or .png: the finest level at 8 bits, (N + 1) / 2")
      ->capture_default_str()
      ->check(kNotEmpty)
      ->check(kExrOrPngPath);
  nm->add_option("--scale", opt->scale, "height scale: F = scale · h")->capture_default_str()->check(finite_in(0.0, 1e6));
  nm->add_option("--k", opt->k, "square patch: |Pu| = |Pv| = k (square form)")->capture_default_str()->check(
      finite_in(1e-6, 1e6));
  nm->add_option("--surface", opt->surface,
                 "the surface whose Pu, Pv the general form needs: plane, sphere, torus or a mesh file")
      ->check(kNotEmpty);
  nm->add_option("--form", opt->form, "square (default without --surface), tangent (default with it) or object")
      ->check(CLI::IsMember({"square", "tangent", "object"}));
  nm->add_option("--wrap", opt->wrap, "border handling of the derivatives and the texture")
      ->capture_default_str()->check(CLI::IsMember({"repeat", "clamp"}));
  nm->add_flag("--no-renormalize", opt->keep_mip_lengths, "keep the mip levels' averaged normals as they are");
  auto maps = std::make_shared<std::vector<std::pair<CLI::App*, std::function<int()>>>>();
  add_map_precompute(cmd, *maps);
  return {cmd, [opt, maps]() {
            for (const auto& [sub, run] : *maps)
              if (sub->parsed()) return run();
            Progress progress("precompute normalmap");
            progress.phase("loading the height map");
            require_output("--output", opt->output);
            check_outputs({{"--output", opt->output}}, {opt->height, opt->surface});
            core::Texture height = core::load_texture_file(opt->height);
            height.wrap = opt->wrap == "repeat" ? core::Wrap::Repeat : core::Wrap::Clamp;
            core::check_height_map(height, opt->height, "");
            const std::string form = !opt->form.empty() ? opt->form : opt->surface.empty() ? "square" : "tangent";
            if (form != "square" && opt->surface.empty())
              throw core::InputError(opt->height, "--surface", "the " + form + " form needs the surface (--surface)");
            progress.phase("building the normal map");
            const auto start = std::chrono::steady_clock::now();
            core::Texture base;
            if (form == "square") {
              base = core::square_normal_map(height, opt->scale, opt->k);
            } else {
              base = core::surface_normal_map(height, opt->scale, surface_mesh(opt->surface),
                                              form == "tangent" ? core::NormalMapForm::Tangent
                                                                : core::NormalMapForm::Object);
            }
            const std::vector<core::Texture> levels = core::mip_levels(base, !opt->keep_mip_lengths);
            const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            const bool png = has_extension(opt->output, ".png");
            progress.phase("writing");
            if (png) {
              core::OutputSet out;
              out.write(opt->output, normal_map_png(base));
              out.commit();
            } else {
              core::write_mip_chain(opt->output, base, levels,
                                  {{"shadetlm:version", core::kVersion},
                                   {"shadetlm:normalmap.form", form},
                                   {"shadetlm:normalmap.height", opt->height},
                                   {"shadetlm:normalmap.scale", std::to_string(opt->scale)},
                                   {"shadetlm:normalmap.k", form == "square" ? std::to_string(opt->k) : "-"},
                                   {"shadetlm:normalmap.surface", opt->surface},
                                   {"shadetlm:normalmap.wrap", opt->wrap},
                                   {"shadetlm:normalmap.renormalized", opt->keep_mip_lengths ? "no" : "yes"}});
            }
            progress.done();
            std::cout << "precompute normalmap: " << opt->height << " (" << height.width << "x" << height.height
                      << "), " << form << " form, "
                      << (png ? std::string("the finest level at 8 bits") : std::to_string(levels.size() + 1) + " levels")
                      << ", " << core::figure(seconds) << " s\n"
                      << "  wrote " << opt->output << "\n";
            return 0;
          }};
}

}  // namespace shadetlm::app
