// Subcommand dispatch (see command.h).

#include "app/command.h"

#include <CLI/CLI.hpp>
#include <cstdio>

#include "app/scene.h"

namespace weft::app {

int dispatch(CLI::App& app, const std::vector<Command>& commands, int argc, char** argv) {
  try {
    try {
      app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
      if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
      std::fprintf(stderr, "weft: error: %s (see weft --help)\n", e.what());
      for (const Command& c : commands)
        if (c.cli->parsed()) return c.parse_error_code;
      return exit_bad_input;
    }
    for (const Command& c : commands) {
      if (!c.cli->parsed()) continue;
      return c.run();
    }
  } catch (const SceneError& e) {
    std::fprintf(stderr, "weft: error: %s\n", e.what());
    return exit_bad_input;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "weft: error: %s\n", e.what());
    return exit_failure;
  }
  return exit_ok;
}

std::string joined_command_line(int argc, char** argv) {
  std::string line;
  for (int i = 0; i < argc; ++i) line += (i ? " " : "") + std::string(argv[i]);
  return line;
}

}  // namespace weft::app
