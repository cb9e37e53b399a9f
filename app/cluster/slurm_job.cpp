// Slurm job scripts and their submission (see slurm_job.h).

#include "app/cluster/slurm_job.h"

#include <array>
#include <cctype>
#include <fstream>
#include <cstdio>
#include <stdexcept>


#include "app/io/input_error.h"
#include "app/io/output_files.h"

namespace weft::app {

namespace {

std::string command_words(const std::vector<std::string>& argv) {
  std::string s;
  for (const std::string& word : argv) s += (s.empty() ? "" : " ") + shell_quoted(word);
  return s;
}

// The value in single quotes with control characters written as \n, \t or \xNN, so that an
// error message naming it stays on one line.
std::string printable(const std::string& value) {
  std::string out = "'";
  for (const char c : value) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\n') out += "\\n";
    else if (c == '\t') out += "\\t";
    else if (u < 0x20 || u == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", u);
      out += hex;
    } else out += c;
  }
  return out + "'";
}

// One "#SBATCH --KEY=VALUE" line. sbatch reads a directive's value up to white space or '#'
// unless it is quoted, and takes a backslash as an escape, so the value is written in double
// quotes with '"' and '\' escaped. A line break cannot be quoted (the rest of the value would be
// a bash command when the script runs), so a value with any control character is refused.
std::string directive(const std::string& key, const std::string& value) {
  std::string quoted = "\"";
  for (const char c : value) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      throw InputError(printable(value) + ": a Slurm script cannot name a path or value with a line "
                       "break or another control character in it (its #SBATCH --" + key +
                       " line would end there); rename it or choose another folder");
    if (c == '"' || c == '\\') quoted += '\\';
    quoted += c;
  }
  return "#SBATCH --" + key + "=" + quoted + "\"\n";
}

// A path as a literal part of a Slurm file name pattern (--output): '%' starts a pattern
// there (%a, %j, …), so each is doubled.
std::string literal_filename(const std::filesystem::path& path) {
  std::string out;
  for (const char c : path.string()) out += c == '%' ? std::string("%%") : std::string(1, c);
  return out;
}

std::string header(const std::string& job_name, const SlurmResources& r,
                   const std::filesystem::path& chdir) {
  std::string s = directive("job-name", job_name);
  if (!chdir.empty()) s += directive("chdir", chdir.string());
  s += "#SBATCH --ntasks=1\n";
  s += "#SBATCH --cpus-per-task=" + std::to_string(r.cpus) + "\n";
  if (r.memory_mb > 0) s += "#SBATCH --mem=" + std::to_string(r.memory_mb) + "M\n";
  if (r.time_minutes > 0) s += "#SBATCH --time=" + slurm_time(r.time_minutes) + "\n";
  return s;
}

}  // namespace

std::string shell_quoted(const std::string& word) {
  std::string out = "'";
  for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string slurm_array_script(const SlurmArray& a) {
  if (a.tasks.empty()) throw std::invalid_argument("slurm_array_script: no tasks");
  const std::string first = std::to_string(first_slurm_array_index);
  const std::string last = std::to_string(first_slurm_array_index + static_cast<int>(a.tasks.size()) - 1);
  if (first_slurm_array_index + static_cast<long>(a.tasks.size()) - 1 > max_slurm_array_index)
    throw InputError(std::to_string(a.tasks.size()) + " tasks from index " + first +
                     ": more than a Slurm array holds (sbatch's default MaxArraySize of 1001 "
                     "allows indices up to 1000); split the work");
  std::string s = "#!/bin/bash\n";
  s += "# Written by weft: task i of the array runs command i below; resubmit one with\n";
  s += "#   sbatch --array=I THIS_SCRIPT\n";
  if (!a.resources.basis.empty()) s += "# Resources per task: " + a.resources.basis + "\n";
  s += header(a.job_name, a.resources, a.chdir);
  s += "#SBATCH --array=" + first + "-" + last + "\n";
  s += directive("output", literal_filename(a.log_dir / a.job_name) + "_%a.log");
  s += "set -eu\n";
  s += "case \"${SLURM_ARRAY_TASK_ID:?set by Slurm: the task to run}\" in\n";
  for (std::size_t i = 0; i < a.tasks.size(); ++i)
    s += "  " + std::to_string(first_slurm_array_index + static_cast<int>(i)) + ") exec " +
         command_words(a.tasks[i]) + " ;;\n";
  s += "  *) echo \"weft: no task $SLURM_ARRAY_TASK_ID in this array (" + first + "-" + last +
       ")\" >&2; exit 1 ;;\n";
  s += "esac\n";
  return s;
}

std::string slurm_job_script(const SlurmJob& job) {
  std::string s = "#!/bin/bash\n";
  s += "# Written by weft: one job; run it again with sbatch THIS_SCRIPT\n";
  if (!job.resources.basis.empty()) s += "# Resources: " + job.resources.basis + "\n";
  s += header(job.job_name, job.resources, job.chdir);
  s += directive("output", literal_filename(job.log));
  s += "set -eu\n";
  s += "exec " + command_words(job.argv) + "\n";
  return s;
}

void write_slurm_script(const std::filesystem::path& path, const std::string& text) {
  std::filesystem::create_directories(path.parent_path());
  write_text(path, text);
  std::filesystem::permissions(path, std::filesystem::perms::owner_exec,
                               std::filesystem::perm_options::add);
}

std::string submit_slurm_script(const std::filesystem::path& path,
                                const std::optional<std::string>& after) {
  const std::string command =
      "sbatch " + (after ? "--dependency=afterany:" + *after + " " : std::string()) +
      shell_quoted(path.string()) + " 2>&1";
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

std::string submitted_job_id(const std::string& output) {
  const std::string prefix = "Submitted batch job ";
  const std::size_t at = output.find(prefix);
  std::size_t end = at == std::string::npos ? at : at + prefix.size();
  while (end != std::string::npos && end < output.size() && std::isdigit(static_cast<unsigned char>(output[end]))) ++end;
  if (at == std::string::npos || end == at + prefix.size())
    throw std::runtime_error("sbatch gave no job id: " + output);
  return output.substr(at + prefix.size(), end - at - prefix.size());
}

void check_slurm_scripts(const SlurmArray& array, const SlurmJob& collect) {
  slurm_array_script(array);
  slurm_job_script(collect);
}

std::string write_slurm_array(const SlurmArray& array, const std::filesystem::path& path,
                              bool dry_run) {
  const std::string text = slurm_array_script(array);  // refuses a bad path before any write
  std::filesystem::create_directories(array.log_dir);
  write_slurm_script(path, text);
  return dry_run ? std::string() : submit_slurm_script(path);
}

void submit_array_and_collect(const SlurmArray& array, const std::filesystem::path& array_script,
                              const SlurmJob& collect, const std::filesystem::path& collect_script,
                              bool dry_run) {
  const std::string collect_text = slurm_job_script(collect);
  write_slurm_script(collect_script, collect_text);
  const std::string submitted = write_slurm_array(array, array_script, dry_run);
  std::fprintf(stderr, "weft: wrote %s (%zu array tasks) and %s (the collect job)%s\n",
               array_script.c_str(), array.tasks.size(), collect_script.c_str(),
               dry_run ? " (not submitted: --dry-run)" : "");
  if (dry_run) {
    std::printf("# %s\n%s\n# %s\n%s\n# to submit them:\n", array_script.c_str(),
                slurm_array_script(array).c_str(), collect_script.c_str(), collect_text.c_str());
    std::printf("job=$(sbatch --parsable %s)\nsbatch --dependency=afterany:${job%%%%;*} %s\n",
                shell_quoted(array_script.string()).c_str(),
                shell_quoted(collect_script.string()).c_str());
    return;
  }
  const std::string id = submitted_job_id(submitted);
  std::printf("%s%s", submitted.c_str(), submit_slurm_script(collect_script, id).c_str());
}

void record_submission(const std::filesystem::path& dir, const std::string& command_line) {
  std::filesystem::create_directories(dir / "slurm");
  write_text(dir / "slurm" / "command.txt", command_line + "\n");
}

std::string submitted_command_line(const std::filesystem::path& dir, const std::string& own) {
  std::ifstream in(dir / "slurm" / "command.txt");
  std::string line;
  return in && std::getline(in, line) ? line : own;
}

}  // namespace weft::app
