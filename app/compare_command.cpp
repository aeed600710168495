// shadetlm compare A.exr B.exr [--layer RGB|A|Z|N] [--fail T] [--failpercent P]
//                  [--hardfail H] [--diff diff.exr] [--json]
#include <cmath>
#include <cstdlib>
#include <iostream>

#include "app/commands.hpp"
#include "shadetlm/core/compare.hpp"
#include "shadetlm/core/input_error.hpp"

namespace shadetlm::app {

namespace {
struct Options {
  std::string a, b, diff, images;
  core::CompareOptions compare;
  bool json = false;
};

// Per layer: the figures over the covered pixels, then the frame-wide ones, then the verdict's count.
void print_figures(const core::CompareResult& r, double fail) {
  using core::figure;
  const core::Coverage& c = r.coverage;
  if (!r.layers.empty())
    std::cout << "covered (" << (c.source == "none" ? "no A or Z: every pixel" : c.source) << "): " << c.a << " pixels in A, "
              << c.b << " in B, " << c.either << " in either, " << c.differ << " in one only\n";
  for (const auto& m : r.layers)
    std::cout << m.layer << ": max " << figure(m.max_abs) << " at (" << m.max_x << ", " << m.max_y << "), rmse "
              << figure(m.rmse) << ", psnr " << figure(m.psnr) << " dB over " << m.pixels
              << " covered pixels; frame-wide: max " << figure(m.frame_max) << ", rmse " << figure(m.frame_rmse)
              << ", psnr " << figure(m.frame_psnr) << " dB; " << figure(m.over_percent) << " % of the frame's pixels over "
              << figure(fail) << (m.pass ? "" : "  FAIL") << "\n";
}
// Compares, writes the difference and images, then prints the figures and verdict.
int run_compare(const Options& opt) {
  const core::Frame a = core::read_exr(opt.a), b = core::read_exr(opt.b);
  const std::string& p = opt.images;
  check_outputs({{"--diff", opt.diff},
                 {"--images", p.empty() ? "" : p + "-new.png"},
                 {"--images", p.empty() ? "" : p + "-reference.png"},
                 {"--images", p.empty() ? "" : p + "-diff.png"},
                 {"--images", p.empty() ? "" : p + "-heat.png"}},
                {opt.a, opt.b});
  if (!p.empty())
    for (const auto& [file, frame] : {std::pair{opt.a, &a}, std::pair{opt.b, &b}})
      if (!frame->find("R") || !frame->find("G") || !frame->find("B"))
        throw core::InputError(file, "--images", "the frame has no R, G, B channels to draw");
  core::CompareOptions o = opt.compare;
  o.threads = threads();
  const core::CompareResult r = core::compare_frames(a, b, o);
  if (!r.problem.empty()) {  // not comparable: trouble, as a missing file is
    std::cerr << "shadetlm: compare " << opt.a << " " << opt.b << ": " << r.problem << "\n";
    return 2;
  }
  core::OutputSet outputs;  // the difference and the images together, or none, before the verdict
  if (!opt.diff.empty()) add_frame(outputs, core::difference_frame(a, b, r), opt.diff, "");
  if (!p.empty()) core::add_comparison_images(outputs, p, a, b, opt.compare.fail);
  outputs.commit();
  if (opt.json) {
    std::cout << r.to_json().dump(2) << "\n";
  } else {
    print_figures(r, opt.compare.fail);
    std::cout << r.verdict() << "\n";
  }
  return r.pass ? 0 : 1;  // (as diff, cmp and idiff: 1 different, 2 trouble)
}
}  // namespace

Command add_compare_command(CLI::App& app) {
  auto opt = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "compare", "compare two EXR frames per layer (B is the reference); exit 0 pass, 1 fail, 2 trouble");
  cmd->add_option("a", opt->a, "frame under test")->required();
  cmd->add_option("b", opt->b, "reference frame")->required();
  cmd->add_option("--layer", opt->compare.layers, "layers to compare (default: all present)")
      ->check(CLI::IsMember({"RGB", "A", "Z", "N", "UV", "H"}));
  // NaN would make every comparison pass (or fail): thresholds are finite numbers ≥ 0.
  const CLI::Validator threshold = finite_in(0, 1e300);
  cmd->add_option("--fail", opt->compare.fail, "a pixel fails over this absolute error")
      ->check(threshold)->capture_default_str();
  cmd->add_option("--failpercent", opt->compare.fail_percent, "the layer fails when more than this % of pixels fail")
      ->check(threshold)->capture_default_str();
  cmd->add_option("--hardfail", opt->compare.hard_fail, "the layer fails when any pixel's error is over this")
      ->check(threshold);
  cmd->add_option("--diff", opt->diff, "write |A - B| per channel to this EXR")
      ->check(kNotEmpty)
      ->check(kExrPath);
  cmd->add_flag("--json", opt->json, "print the metrics as JSON");
  cmd->add_option("--images", opt->images,
                  "write PREFIX-new.png, -reference.png, -diff.png (|A-B| x16) and -heat.png (error heat map)")
      ->check(kNotEmpty);
  return {cmd, [opt]() {
            try {
              return run_compare(*opt);
            } catch (const core::InputError&) {
              throw;  // bad input: exit 2, from main
            } catch (const std::exception& e) {  // a failed write, an allocation: trouble, never "different"
              std::cerr << "shadetlm: compare: " << e.what() << "\n";
              return 2;
            }
          }};
}

}  // namespace shadetlm::app
