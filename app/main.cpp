// The `weft` command: each subcommand registers itself (app/command.h); main lists them in the
// order `weft --help` shows and dispatches.
#include <CLI/CLI.hpp>
#include <cstdio>

#include "app/command.h"
#include "app/compare_command.h"
#include "app/diff_command.h"
#include "app/fit_command.h"
#include "app/folds_command.h"
#include "app/gallery_command.h"
#include "app/measure_command.h"
#include "app/run_command.h"
#include "app/stability_command.h"
#include "app/sweep_command.h"
#include "app/turntable_command.h"
#include "app/version.h"

int main(int argc, char** argv) {
  using namespace weft::app;
  CLI::App app{"weft: offline cloth simulation and visualization.\n"
               "Simulates a scene file and writes a PNG sequence, stats.csv and a copy of the scene."};
  app.set_version_flag("--version", std::string("weft ") + version());
  app.require_subcommand(1);
  const std::string line = joined_command_line(argc, argv);
  const std::vector<Command> commands = {
      register_run(app, line),     register_stability(app, line), register_sweep(app, line),
      register_measure(app, line), register_folds(app, line),     register_turntable(app, line),
      register_diff(app, line),    register_compare(app, line),   register_gallery(app, line),
      register_fit(app, line),
  };
  if (argc == 1) {  // no command: say what there is
    std::fputs(app.help().c_str(), stdout);
    return exit_bad_input;
  }
  return dispatch(app, commands, argc, argv);
}
