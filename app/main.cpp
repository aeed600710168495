// shadetlm: the SystemC/TLM-2.0 shading-pipeline model and its tools.
#include <iostream>

#include "app/commands.hpp"
#include "core/input_error.hpp"
#include "core/version.hpp"

int main(int argc, char** argv) {
  CLI::App app{"shadetlm: a SystemC/TLM-2.0 model of a per-pixel shading pipeline"};
  app.set_version_flag("--version", core::kVersion);
  app.require_subcommand(1);
  std::vector<app::Command> commands = {app::add_reference_command(app),
                                        app::add_compare_command(app)};
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  try {
    for (const auto& command : commands)
      if (command.cli->parsed()) return command.run();
  } catch (const core::InputError& e) {
    std::cerr << "shadetlm: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "shadetlm: " << e.what() << "\n";
    return 1;
  } catch (...) {
    std::cerr << "shadetlm: an unknown error\n";
    return 1;
  }
  return 1;
}
