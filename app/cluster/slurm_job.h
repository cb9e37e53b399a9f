#pragma once
// Slurm jobs: bash scripts for `sbatch`. A job array's task i runs one weft
// command line of a list — the array index picks it — so that the tasks are independent and
// each can be resubmitted alone (`sbatch --array=I SCRIPT`); a single job (a sweep's or
// gallery's collect job) runs one command line, submitted to start after the array
// (`--dependency=afterany:ID`: when every task has ended, failed or not). `weft render --slurm`,
// `weft sweep --slurm` and `weft gallery --slurm` write them (docs/cluster.md). Since an sbatch
// script is a bash script, running it with SLURM_ARRAY_TASK_ID=i set does task i on this machine.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/cluster/slurm_resources.h"

namespace weft::app {

struct SlurmArray {
  std::string job_name;                         // #SBATCH --job-name
  std::vector<std::vector<std::string>> tasks;  // each task's argv (argv[0]: the program)
  std::filesystem::path log_dir;                // task i logs to log_dir/<job_name>_<i>.log
  SlurmResources resources;                     // per task
  std::filesystem::path chdir;                  // #SBATCH --chdir, if not empty
};

struct SlurmJob {
  std::string job_name;
  std::vector<std::string> argv;
  std::filesystem::path log;  // its stdout and stderr
  SlurmResources resources;
  std::filesystem::path chdir;  // #SBATCH --chdir, if not empty
};

// Array tasks are numbered from 1, as weft numbers frames, runs and scenes: task k (from 1) runs
// `tasks[k - 1]` (render: the k-th part of the frames, sweep: run k, gallery: scene k).
inline constexpr int first_slurm_array_index = 1;
// The largest array index sbatch accepts with Slurm's default MaxArraySize (1001).
inline constexpr int max_slurm_array_index = 1000;

// The word quoted for bash: 'text' with each ' written as '\''.
std::string shell_quoted(const std::string& word);

// The script's text. Throws std::invalid_argument for an array without tasks, and InputError
// naming the path for a folder, log or job name with a line break or another control
// character (an #SBATCH directive cannot hold one: the rest of the line would run as a
// command), and for an array index over max_slurm_array_index; every directive's value is
// quoted.
std::string slurm_array_script(const SlurmArray& array);
std::string slurm_job_script(const SlurmJob& job);

// Throws as the two functions above would, before a command changes anything for a submission.
void check_slurm_scripts(const SlurmArray& array, const SlurmJob& collect);

// Writes `text` to `path` as an executable script (creating its folder).
void write_slurm_script(const std::filesystem::path& path, const std::string& text);

// Submits a written script with sbatch (`sbatch [--dependency=afterany:AFTER] PATH`) and returns
// sbatch's output ("Submitted batch job N"); a missing sbatch or a refusal is a
// std::runtime_error saying so.
std::string submit_slurm_script(const std::filesystem::path& path,
                                const std::optional<std::string>& after = std::nullopt);

// The job id in sbatch's "Submitted batch job N"; std::runtime_error when there is none.
std::string submitted_job_id(const std::string& sbatch_output);

// Writes the array's script to `path` (executable) and, unless dry_run, submits it with sbatch,
// returning sbatch's output.
std::string write_slurm_array(const SlurmArray& array, const std::filesystem::path& path,
                              bool dry_run);

// An array and its collect job: writes both scripts beside each other, and unless dry_run
// submits the array, then the collect job to run after it (afterany). Prints, on stdout, the
// scripts and the sbatch commands (dry_run) or sbatch's answers; on stderr what it wrote.
void submit_array_and_collect(const SlurmArray& array, const std::filesystem::path& array_script,
                              const SlurmJob& collect, const std::filesystem::path& collect_script,
                              bool dry_run);

// The command line a submission was made with, kept in DIR/slurm/command.txt for the collect
// job's records (run.txt, README.md): record_submission writes it, submitted_command_line reads
// it back (`own` when there is none).
void record_submission(const std::filesystem::path& dir, const std::string& command_line);
std::string submitted_command_line(const std::filesystem::path& dir, const std::string& own);

}  // namespace weft::app
