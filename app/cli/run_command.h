#pragma once
// `weft run`: simulate a scene and write its PNG sequence, stats.csv and a copy of the scene
// (the job: app/run/run_job.h).

#include <string>

#include "app/cli/command.h"

namespace weft::app {

// Adds `weft run` to the command line.
Command register_run(CLI::App& app, const std::string& command_line);

}  // namespace weft::app
