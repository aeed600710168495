#include "shadetlm/core/nearest.hpp"

#include <algorithm>

namespace shadetlm::core {

size_t edit_distance(const std::string& a, const std::string& b) {
  // Three rows of the table (a swap looks two back).
  std::vector<size_t> before(b.size() + 1), last(b.size() + 1), row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) last[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      row[j] = std::min({last[j] + 1, row[j - 1] + 1, last[j - 1] + (a[i - 1] != b[j - 1])});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) row[j] = std::min(row[j], before[j - 2] + 1);
    }
    std::swap(before, last), std::swap(last, row);
  }
  return last[b.size()];
}

std::string nearest_name(const std::string& word, const std::vector<std::string>& names) {
  std::string best;
  // (-x: every short option is one letter away; past 64 letters no name is a typo of it)
  if (word.size() <= 2 || word.size() > 64) return best;
  size_t best_distance = std::max<size_t>(2, word.size() / 3) + 1;
  for (const auto& n : names) {
    const size_t apart = n.size() > word.size() ? n.size() - word.size() : word.size() - n.size();
    if (apart >= best_distance) continue;  // at least that many edits
    if (const size_t d = edit_distance(word, n); d < best_distance) best = n, best_distance = d;
  }
  return best;
}

}  // namespace shadetlm::core
