// weft sweep: simulate each combination of --set values, compare each final frame with the
// reference run's (app/sweep/sweep_merge.h) and report the speed/accuracy trade — here, one point
// after another, or as a Slurm job array and a collect job (--slurm; docs/cluster.md).

#include "app/cli/sweep_command.h"

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include <CLI/CLI.hpp>
#include <algorithm>

#include "app/io/input_guard.h"
#include "app/scene/scene_inputs.h"
#include "app/scene/scene.h"
#include "app/scene/scene_patch.h"
#include "app/cluster/slurm_job.h"
#include "app/cluster/slurm_resources.h"
#include "app/sweep/sweep_merge.h"
#include "app/sweep/sweep_point.h"
#include "sim/simulator.h"

namespace weft::app {

namespace {

namespace fs = std::filesystem;

// Test hooks (environment variables, docs/cluster.md "Testing"), read where a point runs:
// WEFT_SWEEP_FAIL_RUNS=2,5 makes those runs throw, as a task that dies would;
// WEFT_SWEEP_SECONDS_PER_VERTEX_STEP=S records S × vertices × steps as a run's wall time, so
// that sweep.csv and sweep.png are the same bits wherever and however the points ran.
bool failing_on_purpose(std::size_t k) {
  const char* runs = std::getenv("WEFT_SWEEP_FAIL_RUNS");
  std::stringstream list(runs ? runs : "");
  for (std::string item; std::getline(list, item, ',');)
    if (item == std::to_string(k)) return true;
  return false;
}

// Simulates run k (1-based).
void simulate_point(SweepRun& run, std::size_t k) {
  if (failing_on_purpose(k))
    throw std::runtime_error("failing on purpose (WEFT_SWEEP_FAIL_RUNS)");
  simulate(run);
  if (const char* cost = std::getenv("WEFT_SWEEP_SECONDS_PER_VERTEX_STEP"))
    run.wall_s = std::strtod(cost, nullptr) * static_cast<double>(run.mesh.vertex_count()) *
                 static_cast<double>(run.steps);
}

fs::path output_dir(const SweepOptions& options, const Scene& base) {
  return options.out.value_or(fs::path("out") / ("sweep-" + base.name));
}

// The command line of a task (--point K) or the collect job (--collect): the sweep's own
// options, with absolute paths.
std::vector<std::string> sweep_argv(const SweepOptions& options, const fs::path& dir,
                                    const std::vector<std::string>& mode) {
  std::vector<std::string> argv{fs::read_symlink("/proc/self/exe").string(), "sweep"};
  if (options.scene) argv.push_back(fs::absolute(*options.scene).string());
  for (const std::string& set : options.set) argv.insert(argv.end(), {"--set", set});
  argv.insert(argv.end(), {"--out", fs::absolute(dir).string()});
  for (const Setting& s : options.overrides)  // only --frames adds one
    argv.insert(argv.end(), {"--frames", s.value});
  if (options.threads) argv.insert(argv.end(), {"--threads", std::to_string(*options.threads)});
  if (options.reference)
    argv.insert(argv.end(), {"--reference", std::to_string(*options.reference)});
  argv.insert(argv.end(), mode.begin(), mode.end());
  return argv;
}

int submit_sweep(const SweepOptions& options, const std::vector<SweepRun>& runs, const fs::path& dir) {
  const fs::path slurm_dir = fs::absolute(dir / "slurm");
  std::vector<TaskWork> works;
  long vertices = 0;
  for (const SweepRun& run : runs) {
    works.push_back(scene_work(run.scene, false));
    vertices += works.back().vertices;
  }
  SlurmArray array;
  array.job_name = "weft-sweep";
  array.log_dir = slurm_dir;
  array.resources = estimate_resources(works, options.threads.value_or(1));
  for (std::size_t k = 1; k <= runs.size(); ++k)
    array.tasks.push_back(sweep_argv(options, dir, {"--point", std::to_string(k)}));
  SlurmJob collect;
  collect.job_name = "weft-sweep-collect";
  collect.argv = sweep_argv(options, dir, {"--collect"});
  collect.log = slurm_dir / "weft-sweep-collect.log";
  TaskWork merge_work;  // every point's last frame and mesh at once
  merge_work.vertices = vertices;
  collect.resources = estimate_resources({merge_work}, 1);
  check_slurm_scripts(array, collect);
  // An earlier submission's results must not be merged as this one's.
  fs::remove_all(dir / "points");
  record_submission(dir, options.command_line);
  submit_array_and_collect(array, slurm_dir / "sweep.sbatch", collect,
                           slurm_dir / "collect.sbatch", options.dry_run);
  return exit_ok;
}

// At most this many points in one sweep (each is a scene read and a run).
constexpr std::size_t max_sweep_points = 10000;

// The number of points, refused before any scene is read when there are more than
// max_sweep_points, or when a Slurm array could not hold them (a sweep's run k is task k):
// a sweep of 10⁶ points used to read scenes for minutes before it wrote anything.
void check_sweep_size(const std::vector<SettingValues>& values, bool slurm) {
  std::size_t points = 1;  // stops growing past the limit, so it cannot overflow
  std::string sizes;
  for (const SettingValues& v : values) {
    if (points <= max_sweep_points) points *= std::max<std::size_t>(v.values.size(), 1);
    sizes += (sizes.empty() ? "" : " x ") + std::to_string(v.values.size());
  }
  const std::size_t limit = slurm ? static_cast<std::size_t>(max_slurm_array_index)
                                  : max_sweep_points;
  if (points > limit)
    throw InputError("--set: " + sizes + " values make more than " + std::to_string(limit) +
                     " points, " +
                     (slurm ? "more than a Slurm array holds (sbatch's default MaxArraySize of "
                              "1001 allows indices up to 1000)"
                            : "the limit of one sweep") +
                     "; split the sweep");
}

}  // namespace

int run_sweep(const SweepOptions& options) {
  Scene base = load_scene_with(options.scene, options.overrides);
  apply_threads(base, options.threads);
  if (options.set.empty())
    throw InputError("--set: expected at least one KEY=V1,V2,... to sweep over");
  std::vector<SettingValues> values;
  for (const std::string& text : options.set) values.push_back(parse_set_option(text));
  check_sweep_size(values, options.slurm);

  // Every combination is read (and so checked) before any is simulated.
  std::vector<SweepRun> runs;
  for (std::vector<Setting>& settings : setting_grid(values)) {
    SweepRun run;
    run.scene = patched_scene(base, settings);
    apply_threads(run.scene, options.threads);
    run.settings = std::move(settings);
    runs.push_back(std::move(run));
  }
  const int n = static_cast<int>(runs.size());
  if (options.reference && (*options.reference < 1 || *options.reference > n))
    throw InputError("--reference: expected a run number in 1.." + std::to_string(n) + ", got " +
                     std::to_string(*options.reference));
  if (options.point && (*options.point < 1 || *options.point > n))
    throw InputError("--point: expected a run number in 1.." + std::to_string(n) + ", got " +
                     std::to_string(*options.point));
  const fs::path dir = output_dir(options, base);
  refuse_overwriting_inputs(dir, {{"sweep.csv", "sweep.png", "scene.json", "run.txt"}, {}},
                            scene_files(base));
  if (options.slurm) return submit_sweep(options, runs, dir);

  SweepMerge merge{&base, values, options.reference, options.command_line, dir};
  if (options.point) {  // a Slurm task: its result for the collect job
    const std::size_t k = static_cast<std::size_t>(*options.point);
    simulate_point(runs[k - 1], k);
    write_sweep_point(dir, k, runs[k - 1]);
    std::fprintf(stderr, "weft sweep: run %zu/%d %s: %.3g s, %ld steps%s%s; wrote %s\n", k, n,
                 sweep_label(runs[k - 1], values).c_str(), runs[k - 1].wall_s, runs[k - 1].steps,
                 runs[k - 1].diverged ? ", diverged: " : "", runs[k - 1].failure.c_str(),
                 sweep_point_file(dir, k).c_str());
    return exit_ok;
  }
  if (options.collect) {
    const fs::path script = fs::absolute(dir / "slurm" / "sweep.sbatch");
    for (std::size_t k = 1; k <= runs.size(); ++k) {
      try {
        read_sweep_point(dir, k, runs[k - 1]);
      } catch (const std::exception& e) {
        runs[k - 1].failed = true;
        runs[k - 1].failure = std::string(e.what()) + "; its log: " +
                              (script.parent_path() / ("weft-sweep_" + std::to_string(k) + ".log")).string() +
                              "; resubmit it alone with sbatch --array=" + std::to_string(k) + " " +
                              script.string() + ", then merge again with sbatch " +
                              (script.parent_path() / "collect.sbatch").string();
      }
    }
    merge.command_line = submitted_command_line(dir, options.command_line);
    return merge_sweep(runs, merge);
  }

  std::fprintf(stderr, "weft sweep: %s, %d runs of %d frames each\n", base.source.c_str(), n,
               runs.front().scene.frames);
  for (std::size_t k = 1; k <= runs.size(); ++k) {
    SweepRun& run = runs[k - 1];
    try {
      simulate_point(run, k);
    } catch (const std::exception& e) {
      run.failed = true;
      run.failure = e.what();
    }
    std::fprintf(stderr, "weft sweep: run %zu/%d %s: %.3g s, %ld steps of %.3g ms%s%s\n", k, n,
                 sweep_label(run, values).c_str(), run.wall_s, run.steps, 1e3 * run.time_step_s,
                 run.failed ? ", failed: " : run.diverged ? ", diverged: " : "", run.failure.c_str());
  }
  return merge_sweep(runs, merge);
}

Command register_sweep(CLI::App& app, const std::string& command_line) {
  const auto o = std::make_shared<SweepOptions>();
  o->command_line = command_line;
  CLI::App* cmd = app.add_subcommand(
      "sweep", "Run a scene over a grid of settings; write sweep.csv and sweep.png (error vs wall time)");
  cmd->add_option("scene", o->scene, "Scene file; the built-in default scene if omitted");
  cmd->add_option("--set", o->set,
                  "KEY=V1,V2,...: scene key (dotted path, e.g. cloth.resolution) and the values to "
                  "try (JSON, or plain text such as 1 ms); repeat for a grid of every combination")
      ->required()
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  cmd->add_option("--out", o->out, "Output folder (default: out/sweep-<scene name>)");
  add_override_option(*cmd, "--frames", "output.frames", o->overrides,
                      "Frames to simulate in every run (overrides output.frames)", "INT");
  add_threads_option(*cmd, o->threads);
  cmd->add_option("--reference", o->reference,
                  "Run number (row of sweep.csv) the errors are measured against (default: the "
                  "finest finished run: most cloth vertices, then most steps; the first of "
                  "equals)");
  CLI::Option* slurm = add_slurm_flags(
      *cmd, o->slurm, o->dry_run,
      "Write OUT/slurm/sweep.sbatch (a Slurm job array, one task per point) and "
      "OUT/slurm/collect.sbatch (merges their results after them) and submit both with sbatch");
  // What the Slurm scripts run (in a group of their own: CLI11 names a hidden option nowhere,
  // not even in its errors).
  cmd->add_option("--point", o->point, "Run only this point and leave its result in OUT/points")
      ->group("Run by the --slurm scripts")
      ->excludes(slurm);
  cmd->add_flag("--collect", o->collect, "Merge the results the points left in OUT/points")
      ->group("Run by the --slurm scripts")
      ->excludes(slurm)
      ->excludes("--point");
  return {cmd, [o] { return run_sweep(*o); }};
}

}  // namespace weft::app
