#pragma once
// What every `weft` subcommand shares: its registration — each *_command.cpp adds its own
// subcommand and options to the CLI11 app and returns a Command; app/cli/commands.cpp lists them
// and app/cli/main.cpp dispatches — and the exit codes (app/io/exit_code.h). The options that
// change a scene are in app/cli/options.h.

#include <functional>
#include <string>
#include <vector>

#include "app/io/exit_code.h"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace weft::app {

struct Range;  // app/scene/json_reader.h

// A registered subcommand: the CLI11 subcommand and the job to run when it was parsed. The job
// returns an ExitCode; InputError (bad input) and other exceptions are dispatch's to report.
struct Command {
  CLI::App* cli = nullptr;
  std::function<int()> run;
  int parse_error_code = exit_bad_input;  // exit code of a command-line error
};

// Parses the command line and runs the command that was given: prints help or the version
// (exit 0), a command-line error or bad input as one line "weft: error: …" (the command's
// parse_error_code, or exit_bad_input), another failure as exit_failure.
int dispatch(CLI::App& app, const std::vector<Command>& commands, int argc, char** argv);

// Every command of `weft`, registered on `app` in the order `weft --help` lists them
// (app/cli/main.cpp; tests/app/hostile_input_cli_test.cpp walks their numeric options).
std::vector<Command> register_commands(CLI::App& app, const std::string& command_line);

// The weft program: the app with its version flag and every command, the command line parsed
// and dispatched; with no command, the help and exit_bad_input.
int run_weft(int argc, char** argv);

// Bounds a numeric option: each value must be a finite number in `range`, else a command-line
// error "--NAME: expected a number in …, got 'TEXT'" (NaN and infinities included). Every
// numeric option of every command goes through it or through the scene reader.
CLI::Option* check_range(CLI::Option* option, const Range& range);

// Every option and argument given must have a non-empty value: an empty path ('') is a
// command-line error naming the option rather than a silent default. Returns that error, or
// an empty string.
std::string empty_value_error(const CLI::App& command);

// The command line as typed, with the program spelled "weft" however it was called, recorded
// in the output folders' run.txt, reports and gallery README.
std::string joined_command_line(int argc, char** argv);

}  // namespace weft::app
