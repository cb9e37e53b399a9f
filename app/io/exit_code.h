#pragma once
// Exit codes of the weft command, returned by every job (weft run, measure, sweep, …) and by
// the jobs' parts that decide one (a sweep's merge, a run's divergence).

namespace weft::app {

enum ExitCode : int { exit_ok = 0, exit_bad_input = 1, exit_failure = 2, exit_diverged = 3 };

}  // namespace weft::app
