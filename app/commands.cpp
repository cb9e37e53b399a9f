// The list of weft's commands (see command.h).

#include <CLI/CLI.hpp>

#include "app/command.h"
#include "app/compare_command.h"
#include "app/diff_command.h"
#include "app/fit_command.h"
#include "app/folds_command.h"
#include "app/gallery_command.h"
#include "app/measure_command.h"
#include "app/render_command.h"
#include "app/run_command.h"
#include "app/stability_command.h"
#include "app/sweep_command.h"
#include "app/turntable_command.h"

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
