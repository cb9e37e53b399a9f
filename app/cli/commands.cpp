// The list of weft's commands and the program that dispatches them (see command.h).

#include <CLI/CLI.hpp>
#include <cstdio>

#include "app/cli/command.h"
#include "app/cli/compare_command.h"
#include "app/cli/diff_command.h"
#include "app/cli/fit_command.h"
#include "app/cli/folds_command.h"
#include "app/cli/gallery_command.h"
#include "app/cli/measure_command.h"
#include "app/cli/photo_scene_command.h"
#include "app/cli/render_command.h"
#include "app/cli/run_command.h"
#include "app/cli/stability_command.h"
#include "app/cli/sweep_command.h"
#include "app/cli/turntable_command.h"
#include "app/io/version.h"

namespace weft::app {

std::vector<Command> register_commands(CLI::App& app, const std::string& line) {
  return {
      register_run(app, line),     register_stability(app, line), register_sweep(app, line),
      register_measure(app, line), register_folds(app, line),     register_turntable(app, line),
      register_diff(app, line),    register_compare(app, line),   register_gallery(app, line),
      register_fit(app, line),     register_photo_scene(app, line), register_render(app, line),
  };
}

int run_weft(int argc, char** argv) {
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

}  // namespace weft::app
