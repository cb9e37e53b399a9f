#pragma once
// Slurm job arrays (issue 22 item 3, in part): a bash script for `sbatch` whose task i runs one
// weft command line of a list — the array index picks it — so that the tasks are independent
// and each can be resubmitted alone (`sbatch --array=I SCRIPT`). `weft render --slurm` writes
// one with a frame range per task (docs/checkpoints.md). Since an sbatch script is a bash
// script, running it with SLURM_ARRAY_TASK_ID=i set does task i on this machine.

#include <filesystem>
#include <string>
#include <vector>

namespace weft::app {

struct SlurmArray {
  std::string job_name;                     // #SBATCH --job-name
  std::vector<std::vector<std::string>> tasks;  // each task's argv (argv[0]: the program)
  std::filesystem::path log_dir;            // task i logs to log_dir/<job_name>_<i>.log
  int cpus_per_task = 1;
};

// The word quoted for bash: 'text' with each ' written as '\''.
std::string shell_quoted(const std::string& word);

// The script's text. Throws std::invalid_argument for an array without tasks.
std::string slurm_array_script(const SlurmArray& array);

// Writes the script to `path` (executable) and, unless dry_run, submits it with sbatch,
// returning sbatch's output; a missing sbatch is a std::runtime_error saying so.
std::string write_slurm_array(const SlurmArray& array, const std::filesystem::path& path,
                              bool dry_run);

}  // namespace weft::app
