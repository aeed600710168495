// "Did you mean": the nearest subcommand or option to a mistyped one, for the message
// of a command line CLI11 refused.
#include <algorithm>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "shadetlm/core/input_error.hpp"

namespace shadetlm::app {

namespace {

// Edit distance (insertions, deletions, substitutions; a swap of neighbours counts 1).
size_t distance(const std::string& a, const std::string& b) {
  std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
  for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (size_t i = 1; i <= a.size(); ++i)
    for (size_t j = 1; j <= b.size(); ++j) {
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] != b[j - 1])});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

}  // namespace

std::string nearest(const std::string& word, const std::vector<std::string>& names) {
  std::string best;
  if (word.size() <= 2) return best;  // (-x: every short option is one letter away)
  size_t best_distance = std::max<size_t>(2, word.size() / 3) + 1;
  for (const auto& n : names)
    if (const size_t d = distance(word, n); d < best_distance) best = n, best_distance = d;
  return best;
}

namespace {

std::vector<std::string> option_names(const CLI::App* app) {
  std::vector<std::string> names;
  for (; app; app = app->get_parent())  // (the top level's options reach the subcommands)
    for (const CLI::Option* o : app->get_options()) {
      for (const auto& l : o->get_lnames()) names.push_back("--" + l);
      for (const auto& s : o->get_snames()) names.push_back("-" + s);
    }
  return names;
}

}  // namespace

std::string suggestion(const CLI::App& top, int argc, char** argv) {
  const CLI::App* app = &top;
  bool skip_value = false;  // the token after an option that takes one
  for (int k = 1; k < argc; ++k) {
    const std::string token = argv[k], shown = core::printable(token, 60);  // (echoed: no control bytes)
    if (skip_value) {
      skip_value = false;
      continue;
    }
    if (token.size() > 1 && token[0] == '-') {
      const std::string name = token.substr(0, token.find('='));
      std::vector<std::string> known = option_names(app);
      if (std::find(known.begin(), known.end(), name) == known.end()) {
        const std::string near = nearest(name, known);
        return near.empty() ? "" : "unknown option " + core::printable(name, 60) + " of `" + app->get_name() + "`: did you mean " + near + "?";
      }
      const CLI::Option* o = app->get_option_no_throw(name);
      for (const CLI::App* a = app; !o && a->get_parent(); a = a->get_parent()) o = a->get_parent()->get_option_no_throw(name);
      skip_value = o && o->get_type_size() != 0 && token.find('=') == std::string::npos;
      continue;
    }
    std::vector<std::string> subcommands;
    const CLI::App* chosen = nullptr;
    for (const CLI::App* s : app->get_subcommands([](const CLI::App*) { return true; })) {
      subcommands.push_back(s->get_name());
      if (s->get_name() == token) chosen = s;
    }
    if (subcommands.empty()) continue;  // a positional argument
    if (chosen) {
      app = chosen;
      continue;
    }
    const std::string near = nearest(token, subcommands);
    if (!near.empty()) return "unknown command '" + shown + "': did you mean '" + near + "'?";
    std::string all;
    for (const auto& n : subcommands) all += (all.empty() ? "" : ", ") + n;
    return "unknown command '" + shown + "' (the commands: " + all + ")";
  }
  return "";
}

}  // namespace shadetlm::app
