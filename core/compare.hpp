#pragma once
// The io component (shadetlm::io), all of this header.
// Frame comparison, per layer: RGB (R, G, B, and A when both frames have it), Z
// (depth) and N (N.X, N.Y, N.Z). A pixel's error in a layer is the largest absolute
// difference over the layer's channels; two equal values (infinities included) differ
// by 0, a finite and a non-finite value by +inf.
//
// Verdict (idiff's rule): a layer fails when more than `fail_percent` % of its pixels
// have an error over `fail`, or any pixel has an error over `hard_fail`.
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "shadetlm/core/frame.hpp"

namespace shadetlm::core {

struct CompareOptions {
  std::vector<std::string> layers;  // "RGB", "Z", "N"; empty: every layer either frame has
  double fail = 1e-6;
  double fail_percent = 0;
  double hard_fail = std::numeric_limits<double>::infinity();
};

struct LayerMetrics {
  std::string layer;
  std::vector<std::string> channels;
  double max_abs = 0;
  int max_x = -1, max_y = -1;  // the pixel of max_abs (-1 when no pixel differs)
  double rmse = 0;
  double psnr = 0;             // 10·log10(peak² / MSE); +inf for identical layers
  double peak = 1;             // 1 for RGB and N, the largest finite |Z| of B for Z
  size_t over = 0;             // pixels with an error over `fail`
  double over_percent = 0;
  bool pass = true;
};

struct CompareResult {
  bool pass = true;
  std::string problem;  // a structural mismatch (resolution, channels); empty if none
  std::vector<LayerMetrics> layers;
  nlohmann::json to_json() const;
  std::string verdict() const;  // one line
};

// A figure as JSON, which has no infinity: non-finite values become strings ("inf").
nlohmann::json json_figure(double x);

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
