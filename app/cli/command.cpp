// Subcommand dispatch (see command.h).

#include "app/cli/command.h"

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "app/scene/json_reader.h"
#include "app/scene/scene.h"

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

namespace {

// "unknown command 'rnu' (did you mean 'run'?)" when the first argument names no command, else "".
std::string unknown_command_error(const std::vector<Command>& commands, int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') return "";
  const std::string given = argv[1];
  std::vector<std::string> names;
  for (const Command& c : commands) {
    if (c.cli->get_name() == given) return "";
    names.push_back(c.cli->get_name());
  }
  const std::string best = closest(given, names);
  return "unknown command '" + given + "'" + (best.empty() ? "" : " (did you mean '" + best + "'?)");
}

// "weft run --help" for the command that was parsed, else "weft --help".
std::string help_hint(const std::vector<Command>& commands) {
  for (const Command& c : commands)
    if (c.cli->parsed()) return "weft " + c.cli->get_name() + " --help";
  return "weft --help";
}

}  // namespace

int dispatch(CLI::App& app, const std::vector<Command>& commands, int argc, char** argv) {
  try {
    if (const std::string unknown = unknown_command_error(commands, argc, argv); !unknown.empty()) {
      std::fprintf(stderr, "weft: error: %s; see weft --help\n", unknown.c_str());
      return exit_bad_input;
    }
    try {
      app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
      if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
      std::fprintf(stderr, "weft: error: %s (see %s)\n", e.what(), help_hint(commands).c_str());
      for (const Command& c : commands)
        if (c.cli->parsed()) return c.parse_error_code;
      return exit_bad_input;
    }
    for (const Command& c : commands) {
      if (!c.cli->parsed()) continue;
      if (const std::string error = empty_value_error(*c.cli); !error.empty()) {
        std::fprintf(stderr, "weft: error: %s (see %s)\n", error.c_str(), help_hint(commands).c_str());
        return c.parse_error_code;
      }
      return c.run();
    }
  } catch (const InputError& e) {
    std::fprintf(stderr, "weft: error: %s\n", e.what());
    return exit_bad_input;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "weft: error: %s\n", e.what());
    return exit_failure;
  }
  return exit_ok;
}

std::string joined_command_line(int argc, char** argv) {
  // The program as "weft" however it was called (./build/weft, an installed path): the
  // records and generated pages spell the command one way, as the README does.
  std::string line = "weft";
  for (int i = 1; i < argc; ++i) line += " " + std::string(argv[i]);
  return line;
}

}  // namespace weft::app
