#pragma once
// "Did you mean": the nearest of some names to a mistyped one (a subcommand, an option,
// a setting's key or value), by edit distance.
#include <string>
#include <vector>

namespace shadetlm::core {

// Edit distance: insertions, deletions, substitutions, and a swap of neighbours, 1 each.
size_t edit_distance(const std::string& a, const std::string& b);

// The nearest of `names` to `word`, if near enough to be a typo (at most a third of its
// letters, at least 2, apart); "" if none is, or `word` is too short to tell or too
// long to be a typo (over 64 letters: a hostile file's megabyte key costs nothing).
std::string nearest_name(const std::string& word, const std::vector<std::string>& names);

}  // namespace shadetlm::core
