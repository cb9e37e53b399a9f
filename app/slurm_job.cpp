// Slurm job-array scripts (see slurm_job.h).

#include "app/slurm_job.h"

#include <array>
#include <cstdio>
#include <stdexcept>

#include "app/output_files.h"

namespace weft::app {

std::string shell_quoted(const std::string& word) {
  std::string out = "'";
  for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string slurm_array_script(const SlurmArray& a) {
  if (a.tasks.empty()) throw std::invalid_argument("slurm_array_script: no tasks");
  std::string s = "#!/bin/bash\n";
  s += "# Written by weft: task i of the array runs command i below; resubmit one with\n";
  s += "#   sbatch --array=I THIS_SCRIPT\n";
  s += "#SBATCH --job-name=" + a.job_name + "\n";
  s += "#SBATCH --array=0-" + std::to_string(a.tasks.size() - 1) + "\n";
  s += "#SBATCH --ntasks=1\n";
  s += "#SBATCH --cpus-per-task=" + std::to_string(a.cpus_per_task) + "\n";
  s += "#SBATCH --output=" + (a.log_dir / (a.job_name + "_%a.log")).string() + "\n";
  s += "set -eu\n";
  s += "case \"${SLURM_ARRAY_TASK_ID:?set by Slurm: the task to run}\" in\n";
  for (std::size_t i = 0; i < a.tasks.size(); ++i) {
    s += "  " + std::to_string(i) + ") exec";
    for (const std::string& word : a.tasks[i]) s += " " + shell_quoted(word);
    s += " ;;\n";
  }
  s += "  *) echo \"weft: no task $SLURM_ARRAY_TASK_ID in this array (0-" +
       std::to_string(a.tasks.size() - 1) + ")\" >&2; exit 1 ;;\n";
  s += "esac\n";
  return s;
}

std::string write_slurm_array(const SlurmArray& array, const std::filesystem::path& path,
                              bool dry_run) {
  std::filesystem::create_directories(path.parent_path());
  std::filesystem::create_directories(array.log_dir);
  write_text(path, slurm_array_script(array));
  std::filesystem::permissions(path, std::filesystem::perms::owner_exec,
                               std::filesystem::perm_options::add);
  if (dry_run) return {};
  const std::string command = "sbatch " + shell_quoted(path.string()) + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot run sbatch");
  std::string output;
  std::array<char, 512> buffer{};
  std::size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) output.append(buffer.data(), n);
  const int status = pclose(pipe);
  if (status != 0)
    throw std::runtime_error("sbatch " + path.string() + " failed" +
                             (output.find("not found") != std::string::npos
                                  ? " (no sbatch here: install slurm-wlm, or use --dry-run and "
                                    "submit the script where Slurm runs)"
                                  : "") +
                             ": " + output);
  return output;
}

}  // namespace weft::app
