// "Did you mean": the nearest subcommand or option to a mistyped one, for the message
// of a command line CLI11 refused.
#include <algorithm>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "shadetlm/core/input_error.hpp"
#include "shadetlm/core/nearest.hpp"

namespace shadetlm::app {

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
        const std::string near = core::nearest_name(name, known);
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
    const std::string near = core::nearest_name(token, subcommands);
    if (!near.empty()) return "unknown command '" + shown + "': did you mean '" + near + "'?";
    std::string all;
    for (const auto& n : subcommands) all += (all.empty() ? "" : ", ") + n;
    return "unknown command '" + shown + "' (the commands: " + all + ")";
  }
  return "";
}

}  // namespace shadetlm::app
