#pragma once
// The range of values a datapath carries: what a designer needs to choose its number
// format (the bump-mapping paper's claim that its path needs no wide datapath is about
// these figures). Blocks keep one per datapath and the stats report them.
#include <algorithm>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace shadetlm::modules {

struct ValueRange {
  float lo = std::numeric_limits<float>::infinity(), hi = -std::numeric_limits<float>::infinity();
  void add(const float* v, int n) {
    float l = lo, h = hi;
    for (int i = 0; i < n; ++i) l = std::min(l, v[i]), h = std::max(h, v[i]);
    lo = l, hi = h;
  }
  // A perspective-correct attribute over a span of `count` pixels: a = (a/w)·w, with a/w
  // starting at `a_w` and stepping by `step`. a/w and 1/w are affine along the span and
  // 1/w > 0, so a is monotonic there: its extremes are at the span's two ends.
  void add_span(float a_w, float step, int count, const float* w) {
    if (count <= 0) return;
    const float ends[2] = {a_w * w[0], (a_w + step * float(count - 1)) * w[count - 1]};
    add(ends, 2);
  }
  bool empty() const { return lo > hi; }
  // The largest magnitude: the integer bits a fixed-point datapath needs.
  float magnitude() const { return empty() ? 0.0f : std::max(-lo, hi); }
};

// Named ranges of one block, in the order its datapaths come.
using Ranges = std::vector<std::pair<std::string, ValueRange>>;

inline nlohmann::json to_json(const Ranges& ranges) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [name, r] : ranges)
    if (!r.empty()) j[name] = {r.lo, r.hi};
  return j;
}

}  // namespace shadetlm::modules
