#pragma once
// The io component (shadetlm::io), all of this header.
// Frame comparison, per layer: RGB (R, G, B), A (coverage), Z (depth), N (N.X, N.Y,
// N.Z), and on the parallax path UV (parallax.u, .v: the traced hit) and H
// (parallax.height). A and the hit layers are compared when both frames have them, and
// a frame lacking them is a failure only when they are asked for. A pixel's error in a layer is the largest absolute difference over the layer's
// channels; two equal values (infinities included) differ by 0, a finite and a
// non-finite value by +inf.
//
// The figures (max, RMSE, PSNR) are over the pixels covered in either frame: A ≠ 0, or
// without A a finite Z; a frame with neither counts every pixel as covered. The same
// figures over the whole frame are kept beside them, named frame_* (docs/golden-model.md).
//
// Verdict (idiff's rule), over every pixel of the frame: a layer fails when more than
// `fail_percent` % of the frame's pixels have an error over `fail`, or any pixel has an
// error over `hard_fail`.
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "shadetlm/core/frame.hpp"

namespace shadetlm::core {

struct CompareOptions {
  std::vector<std::string> layers;  // "RGB", "A", "Z", "N", "UV", "H"; empty: every layer either frame has
  double fail = 1e-6;
  double fail_percent = 0;
  double hard_fail = std::numeric_limits<double>::infinity();
  int threads = 1;  // the layers measured at once (0: one per core); the figures are the same for any count
};

struct LayerMetrics {
  std::string layer;
  std::vector<std::string> channels;
  // Over the covered pixels (the headline):
  size_t pixels = 0;           // pixels measured: covered in either frame
  double max_abs = 0;
  int max_x = -1, max_y = -1;  // the pixel of max_abs (-1 when no covered pixel differs)
  double rmse = 0;             // over every measured pixel's every channel
  double psnr = 0;             // 10·log10(peak² / MSE); +inf when MSE is 0
                               // (max, RMSE and PSNR are NaN when no pixel is covered)
  double peak = 1;             // 1 for RGB, A and N; the largest finite |Z| of B for Z
  // Over every pixel of the frame:
  double frame_max = 0, frame_rmse = 0, frame_psnr = 0;
  size_t over = 0;             // pixels with an error over `fail`
  double over_percent = 0;     // of the frame's pixels
  bool pass = true;
};

// Which pixels the figures are over.
struct Coverage {
  std::string source = "none";  // "A", "Z", or "none" (every pixel counts as covered)
  size_t a = 0, b = 0;          // pixels covered in A, in B
  size_t either = 0, differ = 0;  // covered in either; covered in one only
};

struct CompareResult {
  bool pass = true;
  Coverage coverage;
  std::string problem;  // a structural mismatch (resolution, channels); empty if none
  std::vector<LayerMetrics> layers;
  nlohmann::json to_json() const;
  std::string verdict() const;  // one line
};

// A figure as text, 4 significant digits ("inf", "nan" as such): how every error figure is printed.
std::string figure(double x);
// A figure as JSON, which has no infinity: non-finite values become strings ("inf").
nlohmann::json json_figure(double x);
// A layer's figures (max, max_at, rmse, psnr over the covered pixels; pixels; frame: the
// whole frame's) and the coverage, as JSON: what compare --json and render's stats hold.
nlohmann::json layer_json(const LayerMetrics& m);
nlohmann::json coverage_json(const Coverage& c);

// Compares A against B (B is the reference).
CompareResult compare_frames(const Frame& a, const Frame& b, const CompareOptions& options);
// |A − B| for every channel of the compared layers.
Frame difference_frame(const Frame& a, const Frame& b, const CompareResult& result);

// The pictures of a regression report, 8-bit PNGs: `prefix`-new.png and -reference.png
// (sRGB previews of A and B), -diff.png (|A − B| of R, G, B times 16) and -heat.png
// (each pixel's largest colour error on a logarithmic ramp: black below 1e-6, then
// blue, cyan, green, yellow, red at 1e-1 and above; pixels over `fail` are never black).
// (to `outputs`, committed by the caller; both frames need R, G and B)
void add_comparison_images(OutputSet& outputs, const std::string& prefix, const Frame& a, const Frame& b,
                           double fail);

}  // namespace shadetlm::core
