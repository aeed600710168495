#include "shadetlm/core/compare.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "shadetlm/core/parallel.hpp"

namespace shadetlm::core {

namespace {
const std::vector<std::pair<std::string, std::vector<std::string>>>& layer_table() {
  static const std::vector<std::pair<std::string, std::vector<std::string>>> t = {
      {"RGB", {"R", "G", "B"}}, {"A", {"A"}}, {"Z", {"Z"}}, {"N", {"N.X", "N.Y", "N.Z"}},
      {"UV", {"parallax.u", "parallax.v"}}, {"H", {"parallax.height"}}};
  return t;
}

// Which pixels of a frame are covered: A ≠ 0 (NaN counts as covered), or without A a
// finite or −inf Z, or without either every pixel. Returns the rule's name.
std::string covered_pixels(const Frame& f, std::vector<bool>& covered) {
  covered.assign(f.pixel_count(), true);
  if (const Channel* a = f.find("A")) {
    for (size_t i = 0; i < covered.size(); ++i) covered[i] = !(a->values[i] == 0.0f);
    return "A";
  }
  if (const Channel* z = f.find("Z")) {
    for (size_t i = 0; i < covered.size(); ++i) covered[i] = z->values[i] != std::numeric_limits<float>::infinity();
    return "Z";
  }
  return "none";
}

Coverage coverage_of(const Frame& a, const Frame& b, std::vector<bool>& either) {
  std::vector<bool> ca, cb;
  Coverage c;
  const std::string sa = covered_pixels(a, ca), sb = covered_pixels(b, cb);
  c.source = sa == sb ? sa : sa + "/" + sb;
  either.resize(ca.size());
  for (size_t i = 0; i < ca.size(); ++i) {
    c.a += ca[i], c.b += cb[i];
    either[i] = ca[i] || cb[i];
    c.either += either[i];
    c.differ += ca[i] != cb[i];
  }
  return c;
}

double psnr_of(double peak, double mse) {
  return mse == 0 ? std::numeric_limits<double>::infinity() : 10 * std::log10(peak * peak / mse);
}

double difference(float a, float b) {
  if (a == b) return 0;  // also equal infinities
  if (!std::isfinite(a) || !std::isfinite(b)) return std::numeric_limits<double>::infinity();
  return std::abs(double(a) - double(b));
}

}  // namespace

namespace {
LayerMetrics layer_metrics(const Frame& a, const Frame& b, const std::string& layer,
                           const std::vector<std::string>& chans, const std::vector<bool>& covered,
                           const CompareOptions& opt) {
  LayerMetrics m;
  m.layer = layer;
  m.channels = chans;
  if (layer == "Z") {
    m.peak = 0;
    for (float z : b.at("Z"))
      if (std::isfinite(z)) m.peak = std::max(m.peak, double(std::abs(z)));
    if (m.peak == 0) m.peak = 1;
  }
  std::vector<const std::vector<float>*> ca, cb;
  for (const auto& n : chans) {
    ca.push_back(&a.at(n));
    cb.push_back(&b.at(n));
  }
  double sum_sq = 0, frame_sum_sq = 0;
  for (size_t i = 0; i < a.pixel_count(); ++i) {
    double e = 0, sq = 0;
    for (size_t k = 0; k < chans.size(); ++k) {
      const double d = difference((*ca[k])[i], (*cb[k])[i]);
      sq += d * d;
      e = std::max(e, d);
    }
    frame_sum_sq += sq;
    m.frame_max = std::max(m.frame_max, e);
    if (e > opt.fail) ++m.over;
    if (!covered[i]) continue;
    ++m.pixels;
    sum_sq += sq;
    if (e > m.max_abs) {
      m.max_abs = e;
      m.max_x = int(i % size_t(a.width));
      m.max_y = int(i / size_t(a.width));
    }
  }
  // No pixel covered in either frame: no figure (NaN), rather than a perfect one.
  const double mse = m.pixels == 0 ? std::numeric_limits<double>::quiet_NaN()
                                   : sum_sq / (double(m.pixels) * double(chans.size()));
  if (m.pixels == 0) m.max_abs = mse;
  const double frame_mse = a.pixel_count() == 0 ? 0 : frame_sum_sq / (double(a.pixel_count()) * double(chans.size()));
  m.rmse = std::sqrt(mse);
  m.psnr = psnr_of(m.peak, mse);
  m.frame_rmse = std::sqrt(frame_mse);
  m.frame_psnr = psnr_of(m.peak, frame_mse);
  m.over_percent = a.pixel_count() == 0 ? 0 : 100.0 * double(m.over) / double(a.pixel_count());
  m.pass = m.over_percent <= opt.fail_percent && m.frame_max <= opt.hard_fail;
  return m;
}
}  // namespace

CompareResult compare_frames(const Frame& a, const Frame& b, const CompareOptions& opt) {
  CompareResult r;
  if (a.width != b.width || a.height != b.height) {
    r.pass = false;
    r.problem = "resolutions differ: " + std::to_string(a.width) + "x" + std::to_string(a.height) +
                " against " + std::to_string(b.width) + "x" + std::to_string(b.height);
    return r;
  }
  std::vector<bool> covered;
  r.coverage = coverage_of(a, b, covered);
  std::vector<std::pair<std::string, std::vector<std::string>>> measured;  // layers and their channels
  for (const auto& [layer, names] : layer_table()) {
    const bool asked = std::find(opt.layers.begin(), opt.layers.end(), layer) != opt.layers.end();
    // A frame may lack these unless they are asked for: A (the coverage), and the
    // parallax hit (UV, H), which frames written before it was added lack.
    const bool optional = layer == "A" || layer == "UV" || layer == "H";
    std::vector<std::string> chans;
    for (const auto& n : names) {
      const bool in_a = a.find(n) != nullptr, in_b = b.find(n) != nullptr;
      if (in_a && in_b) {
        chans.push_back(n);
      } else if ((in_a || in_b) && ((opt.layers.empty() && !optional) || asked)) {
        r.pass = false;
        r.problem += (r.problem.empty() ? "" : "; ") + std::string("channel ") + n + " is only in " + (in_a ? "A" : "B");
      }
    }
    if (asked && chans.empty()) {
      r.pass = false;
      r.problem += (r.problem.empty() ? "" : "; ") + ("no " + layer + " layer in both frames");
    }
    if (chans.empty() || (!opt.layers.empty() && !asked)) continue;
    measured.emplace_back(layer, chans);
  }
  // Each layer measured whole by one thread, in pixel order: the same sums for any count.
  r.layers.resize(measured.size());
  const int parts = std::max(1, std::min(threads_or_cores(opt.threads), int(measured.size())));
  run_parts(parts, [&](int part) {
    for (size_t k = size_t(part); k < measured.size(); k += size_t(parts))
      r.layers[k] = layer_metrics(a, b, measured[k].first, measured[k].second, covered, opt);
  });
  for (const LayerMetrics& m : r.layers) r.pass = r.pass && m.pass;
  if (r.layers.empty() && r.problem.empty()) {
    r.pass = false;
    r.problem = "no layer (RGB, Z, N) in common";
  }
  return r;
}

Frame difference_frame(const Frame& a, const Frame& b, const CompareResult& result) {
  Frame d(a.width, a.height);
  for (const auto& m : result.layers)
    for (const auto& n : m.channels) {
      std::vector<float>& out = d.add(n);
      const auto &va = a.at(n), &vb = b.at(n);
      for (size_t i = 0; i < out.size(); ++i) out[i] = float(difference(va[i], vb[i]));
    }
  return d;
}

void add_comparison_images(OutputSet& outputs, const std::string& prefix, const Frame& a, const Frame& b,
                           double fail) {
  outputs.write(prefix + "-new.png", png_preview(a));
  outputs.write(prefix + "-reference.png", png_preview(b));
  const char* names[3] = {"R", "G", "B"};
  const size_t n = a.pixel_count();
  std::vector<unsigned char> diff(n * 3), heat(n * 3);
  // The ramp's colours at 1e-6, 1e-5, …, 1e-1.
  const double ramp[6][3] = {{0, 0, 0.5}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}};
  for (size_t i = 0; i < n; ++i) {
    double worst = 0;
    for (int k = 0; k < 3; ++k) {
      const double e = a.find(names[k]) && b.find(names[k]) ? difference(a.at(names[k])[i], b.at(names[k])[i]) : 0.0;
      worst = std::max(worst, e);
      diff[i * 3 + size_t(k)] = static_cast<unsigned char>(std::lround(std::clamp(e * 16.0, 0.0, 1.0) * 255.0));
    }
    double colour[3] = {0, 0, 0};
    if (worst >= 1e-6 || worst > fail) {
      const double t = std::clamp(std::log10(std::max(worst, 1e-6)) + 6.0, 0.0, 5.0);  // 0 … 5
      const int lo = std::min(4, int(t));
      const double f = t - lo;
      for (int k = 0; k < 3; ++k) colour[k] = ramp[lo][k] + (ramp[lo + 1][k] - ramp[lo][k]) * f;
    }
    for (int k = 0; k < 3; ++k) heat[i * 3 + size_t(k)] = static_cast<unsigned char>(std::lround(colour[k] * 255.0));
  }
  outputs.write(prefix + "-diff.png", encode_png(a.width, a.height, diff));
  outputs.write(prefix + "-heat.png", encode_png(a.width, a.height, heat));
}

nlohmann::json json_figure(double x) {
  return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(figure(x));
}

std::string figure(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  std::ostringstream s;
  s.precision(4);
  s << x;
  return s.str();
}

nlohmann::json layer_json(const LayerMetrics& m) {
  const auto num = json_figure;
  return {{"channels", m.channels},
          {"pixels", m.pixels},
          {"max", num(m.max_abs)},
          {"max_at", {m.max_x, m.max_y}},
          {"rmse", num(m.rmse)},
          {"psnr", num(m.psnr)},
          {"peak", m.peak},
          {"frame", {{"max", num(m.frame_max)}, {"rmse", num(m.frame_rmse)}, {"psnr", num(m.frame_psnr)}}}};
}

nlohmann::json coverage_json(const Coverage& c) {
  return {{"source", c.source}, {"a", c.a}, {"b", c.b}, {"either", c.either}, {"differ", c.differ}};
}

nlohmann::json CompareResult::to_json() const {
  nlohmann::json j = {{"pass", pass}, {"layers", nlohmann::json::object()}, {"coverage", coverage_json(coverage)}};
  if (!problem.empty()) j["problem"] = problem;
  for (const auto& m : layers) {
    j["layers"][m.layer] = layer_json(m);
    j["layers"][m.layer]["over"] = m.over;
    j["layers"][m.layer]["over_percent"] = m.over_percent;
    j["layers"][m.layer]["pass"] = m.pass;
  }
  return j;
}

std::string CompareResult::verdict() const {
  std::string s = pass ? "PASS" : "FAIL";
  if (!problem.empty()) s += ": " + problem;
  for (const auto& m : layers)
    s += "  " + m.layer + (m.pass ? "" : "(fail)") + " max " + figure(m.max_abs) + " psnr " + figure(m.psnr) +
         " (frame max " + figure(m.frame_max) + ")";
  return s;
}

}  // namespace shadetlm::core
