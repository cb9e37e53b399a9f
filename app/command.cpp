// Subcommand dispatch (see command.h).

#include "app/command.h"

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "app/json_reader.h"
#include "app/scene.h"

namespace weft::app {

CLI::Option* check_range(CLI::Option* option, const Range& range) {
  const std::string expected =
      range.unbounded() ? "a finite number" : "a number " + range.text();
  return option->check(CLI::Validator(
      [range, expected](std::string& text) -> std::string {
        char* end = nullptr;
        const double x = std::strtod(text.c_str(), &end);
        const bool number = !text.empty() && end == text.c_str() + text.size();
        if (number && std::isfinite(x) && range.contains(x)) return "";
        return "expected " + expected + ", got '" + text + "'";
      },
      range.unbounded() ? "" : range.text()));
}

std::string empty_value_error(const CLI::App& command) {
  for (const CLI::Option* option : command.get_options()) {
    for (const std::string& value : option->results())
      if (value.empty()) return option->get_name() + ": expected a value, got an empty string ''";
  }
  return "";
}

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
      if (const std::string error = empty_value_error(*c.cli); !error.empty()) {
        std::fprintf(stderr, "weft: error: %s (see weft --help)\n", error.c_str());
        return c.parse_error_code;
      }
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
