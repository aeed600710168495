// shadetlm cost [FORMAT ...] [--json]: the area and energy of one operation of each kind
// the model prices, in each number format (docs/silicon.md).
#include <iomanip>
#include <iostream>
#include <stdexcept>

#include "app/commands.hpp"
#include "shadetlm/core/compare.hpp"
#include "shadetlm/core/input_error.hpp"
#include "shadetlm/core/number_format.hpp"
#include "shadetlm/cost/operator_cost.hpp"

namespace shadetlm::app {

namespace {
struct Options {
  std::vector<std::string> formats = {"float32", "float16", "fixed:1.12", "fixed:3.20"};
  bool json = false;
};

// Each format's operations; a format without a figure is refused (exit 2), naming it.
int run_cost(const Options& opt) {
  // (ordered: the formats and operations in the order asked and declared)
  nlohmann::ordered_json j = {{"node", cost::kNode}, {"activity", cost::kActivity},
                              {"formats", nlohmann::ordered_json::object()}};
  for (const std::string& name : opt.formats) {
    core::NumberFormat f;
    try {
      f = core::NumberFormat::parse(name);
    } catch (const std::invalid_argument& e) {
      throw core::InputError("cost", "FORMAT", e.what());
    }
    nlohmann::ordered_json& ops = j["formats"][name];
    for (cost::Operation op : cost::kOperations) {
      const std::optional<cost::OperatorCost> c = cost::operation_cost(op, f);
      if (!c)
        throw core::InputError("cost", "FORMAT", name + " is a " + std::to_string(cost::word_bits(f)) +
                                                     "-bit word: the operators are priced up to " +
                                                     std::to_string(cost::kMaxPricedBits) + " bits");
      ops[cost::name_of(op)] = {{"area_um2", c->area_um2}, {"energy_pj", c->energy_pj}};
    }
  }
  if (opt.json) {
    std::cout << j.dump(2) << "\n";
    return 0;
  }
  std::cout << "one operation in " << cost::kNode << ", inputs switching " << cost::kActivity
            << " times a cycle: area um2, energy pJ\n";
  for (const auto& [name, ops] : j["formats"].items()) {
    std::cout << std::left << std::setw(12) << name << std::right;
    for (const auto& [op, c] : ops.items())
      std::cout << "  " << op << " " << core::figure(c["area_um2"].get<double>()) << " um2 "
                << core::figure(c["energy_pj"].get<double>()) << " pJ";
    std::cout << "\n";
  }
  return 0;
}
}  // namespace

Command add_cost_command(CLI::App& app) {
  auto opt = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("cost", "the area and energy of one operation in each number format");
  cmd->add_option("formats", opt->formats, "number formats: float32, float16, fixed:I.F")->capture_default_str();
  cmd->add_flag("--json", opt->json, "print JSON");
  cmd->footer("Example: shadetlm cost float32 fixed:1.12 --json");
  return {cmd, [opt] { return run_cost(*opt); }};
}

}  // namespace shadetlm::app
