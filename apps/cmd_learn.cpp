// `lcprelax learn block|polygon|scene ...` (docs/cli.md): the parent subcommand. The learning
// applications register themselves (cli_common.hpp, register_learn_application) from
// their own files, so each stays self-contained.
#include "cli_common.hpp"

#include <vector>

namespace lcprelax::cli {
namespace {

std::vector<LearnApplicationFactory>& learn_registry() {
  static std::vector<LearnApplicationFactory> factories;  // constructed on first use
  return factories;
}

}  // namespace

bool register_learn_application(LearnApplicationFactory factory) {
  learn_registry().push_back(factory);
  return true;
}

Command add_learn_command(CLI::App& parent) {
  CLI::App* learn = parent.add_subcommand("learn", "learn contact parameters (friction, mass, inertia, shape) from motion data: block, polygon or scene");
  learn->require_subcommand(1);
  auto applications = std::make_shared<std::vector<Command>>();
  for (LearnApplicationFactory f : learn_registry()) applications->push_back(f(*learn));
  Command command;
  command.app = learn;
  command.run = [applications]() {
    for (const Command& a : *applications)
      if (a.app->parsed()) return a.run();
    return static_cast<int>(kExitBadInput);
  };
  return command;
}

}  // namespace lcprelax::cli
