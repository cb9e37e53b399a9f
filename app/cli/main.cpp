// The `weft` command: each subcommand registers itself (app/cli/command.h), register_commands()
// lists them in the order `weft --help` shows, and main dispatches.
#include <CLI/CLI.hpp>
#include <cstdio>

#include "app/cli/command.h"
#include "app/io/version.h"

int main(int argc, char** argv) {
  using namespace weft::app;
  CLI::App app{"weft: offline cloth simulation and visualization.\n"
               "Simulates a scene file and writes a PNG sequence, stats.csv and a copy of the scene.",
               "weft"};
  app.set_version_flag("--version", std::string("weft ") + version());
  app.require_subcommand(1);
  const std::string line = joined_command_line(argc, argv);
  const std::vector<Command> commands = register_commands(app, line);
  if (argc == 1) {  // no command: say what there is
    std::fputs(app.help().c_str(), stdout);
    return exit_bad_input;
  }
  return dispatch(app, commands, argc, argv);
}
