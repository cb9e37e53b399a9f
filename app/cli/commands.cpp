// The list of weft's commands (see command.h).

#include <CLI/CLI.hpp>

#include "app/cli/command.h"
#include "app/cli/compare_command.h"
#include "app/cli/diff_command.h"
#include "app/cli/fit_command.h"
#include "app/cli/folds_command.h"
#include "app/cli/gallery_command.h"
#include "app/cli/measure_command.h"
#include "app/cli/render_command.h"
#include "app/cli/run_command.h"
#include "app/cli/stability_command.h"
#include "app/cli/sweep_command.h"
#include "app/cli/turntable_command.h"

namespace weft::app {

std::vector<Command> register_commands(CLI::App& app, const std::string& line) {
  return {
      register_run(app, line),     register_stability(app, line), register_sweep(app, line),
      register_measure(app, line), register_folds(app, line),     register_turntable(app, line),
      register_diff(app, line),    register_compare(app, line),   register_gallery(app, line),
      register_fit(app, line),     register_render(app, line),
  };
}

}  // namespace weft::app
