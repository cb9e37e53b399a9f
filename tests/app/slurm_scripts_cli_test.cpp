// Slurm scripts without a cluster: `weft sweep --slurm --dry-run` and `weft gallery --slurm
// --dry-run` print the job array and collect scripts (with resources), and since an sbatch script
// is a bash script, running each task by hand (SLURM_ARRAY_TASK_ID=K bash SCRIPT) and then the
// collect script gives the local run's bytes; a task that fails is listed with the command that
// resubmits it alone, and the other points still merge. tests/app/slurm_cli_test.cpp does the
// same through a real (one-node) Slurm.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/app/slurm_test_support.h"

namespace fs = std::filesystem;

namespace {

using weft::app::test::CliDirectoryTest;
using weft::app::test::CommandResult;
using weft::app::test::file_bytes;
using weft::app::test::run_weft;
using weft::app::test::tiny_scene;

const std::string& kSweep = weft::app::test::kSixPointSweep;
const std::string& kModelTime = weft::app::test::kModelWallTime;
using weft::app::test::shell;

class SlurmScripts : public CliDirectoryTest {
 protected:
  SlurmScripts() : CliDirectoryTest("slurm_scripts_cli") {}
};

TEST_F(SlurmScripts, SweepDryRunPrintsTheArrayAndTheCollectJobWithResources) {
  const fs::path scene = write_scene("tiny.json", tiny_scene());
  const fs::path out = m_dir / "sweep";
  const CommandResult r =
      run_weft("sweep " + scene.string() + kSweep + " --out " + out.string() + " --slurm --dry-run");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* part :
       {"#SBATCH --array=1-6", "#SBATCH --job-name=\"weft-sweep\"", "#SBATCH --cpus-per-task=1",
        "#SBATCH --mem=", "#SBATCH --time=", "# Resources per task: estimated", "'--point' '6'",
        "#SBATCH --job-name=\"weft-sweep-collect\"", "'--collect'", "--dependency=afterany:",
        "not submitted: --dry-run"})
    EXPECT_CONTAINS(r.output, part);
  EXPECT_EQ(r.output.find("'--point' '7'"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(out / "slurm" / "sweep.sbatch"));
  EXPECT_TRUE(fs::exists(out / "slurm" / "collect.sbatch"));
  EXPECT_FALSE(fs::exists(out / "sweep.csv")) << "nothing runs on --dry-run";
}

TEST_F(SlurmScripts, SweepTasksRunByHandMergeIntoTheLocalSweepsBytes) {
  const fs::path scene = write_scene("tiny.json", tiny_scene());
  const fs::path local = m_dir / "local", tasks = m_dir / "tasks";
  const CommandResult l = run_weft("sweep " + scene.string() + kSweep + " --out " + local.string(), kModelTime);
  ASSERT_EQ(l.exit_code, 0) << l.output;
  const CommandResult d = run_weft(
      "sweep " + scene.string() + kSweep + " --out " + tasks.string() + " --slurm --dry-run");
  ASSERT_EQ(d.exit_code, 0) << d.output;
  for (int k = 1; k <= 6; ++k) {
    const CommandResult t = shell(kModelTime + " SLURM_ARRAY_TASK_ID=" + std::to_string(k) +
                                 " bash " + (tasks / "slurm" / "sweep.sbatch").string());
    ASSERT_EQ(t.exit_code, 0) << t.output;
  }
  const CommandResult c = shell("bash " + (tasks / "slurm" / "collect.sbatch").string());
  ASSERT_EQ(c.exit_code, 0) << c.output;
  ASSERT_TRUE(fs::exists(tasks / "sweep.csv"));
  EXPECT_EQ(file_bytes(local / "sweep.csv"), file_bytes(tasks / "sweep.csv"));
  EXPECT_TRUE(file_bytes(local / "sweep.png") == file_bytes(tasks / "sweep.png")) << "plots differ";
  EXPECT_EQ(file_bytes(local / "scene.json"), file_bytes(tasks / "scene.json"));
  // run.txt records the command the user gave, not the collect job's.
  EXPECT_CONTAINS(file_bytes(tasks / "run.txt"), "--slurm --dry-run");
}

TEST_F(SlurmScripts, AFailedSweepTaskIsListedWithItsResubmissionAndTheOthersMerge) {
  const fs::path scene = write_scene("tiny.json", tiny_scene());
  const fs::path local = m_dir / "local", tasks = m_dir / "tasks";
  // --reference: the errors are against the same run whatever the wall times.
  const std::string sweep = kSweep + " --reference 5";
  const CommandResult l = run_weft("sweep " + scene.string() + sweep + " --out " + local.string());
  ASSERT_EQ(l.exit_code, 0) << l.output;
  ASSERT_EQ(run_weft("sweep " + scene.string() + sweep + " --out " + tasks.string() +
                     " --slurm --dry-run").exit_code, 0);
  const fs::path script = fs::absolute(tasks / "slurm" / "sweep.sbatch");
  for (int k = 1; k <= 6; ++k) {
    const CommandResult t = shell("WEFT_SWEEP_FAIL_RUNS=3 SLURM_ARRAY_TASK_ID=" +
                                 std::to_string(k) + " bash " + script.string());
    EXPECT_EQ(t.exit_code == 0, k != 3) << k << ": " << t.output;
  }
  const CommandResult c = shell("bash " + (tasks / "slurm" / "collect.sbatch").string());
  EXPECT_EQ(c.exit_code, 2) << c.output;  // exit_failure: not everything merged
  EXPECT_CONTAINS(c.output, "run 3 (cloth.resolution=[7,7] simulation.integrator=symplectic_euler) failed");
  EXPECT_CONTAINS(c.output, "sbatch --array=3 " + script.string());
  weft::app::test::expect_same_sweep_rows(local / "sweep.csv", tasks / "sweep.csv", 3);
  EXPECT_TRUE(fs::exists(tasks / "sweep.png"));
}

TEST_F(SlurmScripts, GalleryTasksRunByHandGiveTheLocalGallery) {
  fs::create_directories(m_dir / "scenes");
  std::ofstream(m_dir / "scenes" / "a.json") << tiny_scene();
  std::ofstream(m_dir / "scenes" / "b.json")
      << tiny_scene("", R"(, "simulation": {"integrator": "implicit_euler"})");
  const std::string scenes = " --scenes " + (m_dir / "scenes").string();
  // The same --out for both (README.md names it): the local gallery is moved aside.
  const fs::path out = m_dir / "gallery", local = m_dir / "local";
  const CommandResult l = run_weft("gallery" + scenes + " --out " + out.string());
  ASSERT_EQ(l.exit_code, 0) << l.output;
  fs::rename(out, local);
  const CommandResult d = run_weft("gallery" + scenes + " --out " + out.string() + " --slurm --dry-run");
  ASSERT_EQ(d.exit_code, 0) << d.output;
  for (const char* part : {"#SBATCH --array=1-2", "#SBATCH --chdir=", "#SBATCH --mem=",
                           "'--only' 'b' '--task'", "'--collect'", "--dependency=afterany:"})
    EXPECT_CONTAINS(d.output, part);
  for (int k = 1; k <= 2; ++k) {
    const CommandResult t = shell("SLURM_ARRAY_TASK_ID=" + std::to_string(k) + " bash " +
                                 (out / "slurm" / "gallery.sbatch").string());
    ASSERT_EQ(t.exit_code, 0) << t.output;
  }
  const CommandResult c = shell("bash " + (out / "slurm" / "collect.sbatch").string());
  ASSERT_EQ(c.exit_code, 0) << c.output;
  for (const char* name : {"a.png", "a_sheet.png", "b.png", "b_sheet.png"})
    EXPECT_TRUE(file_bytes(local / name) == file_bytes(out / name)) << name << " differs";
  std::string readme = file_bytes(out / "README.md");
  const std::size_t flags = readme.find(" --slurm --dry-run");
  ASSERT_NE(flags, std::string::npos) << readme;  // the command the user gave
  readme.erase(flags, std::string(" --slurm --dry-run").size());
  EXPECT_EQ(readme, file_bytes(local / "README.md"));
}

TEST_F(SlurmScripts, AGalleryTaskThatLeftNoResultIsListedWithItsResubmission) {
  fs::create_directories(m_dir / "scenes");
  std::ofstream(m_dir / "scenes" / "a.json") << tiny_scene();
  std::ofstream(m_dir / "scenes" / "b.json") << tiny_scene();
  const fs::path out = m_dir / "gallery";
  ASSERT_EQ(run_weft("gallery --scenes " + (m_dir / "scenes").string() + " --out " +
                     out.string() + " --slurm --dry-run").exit_code, 0);
  const CommandResult t = shell("SLURM_ARRAY_TASK_ID=1 bash " + (out / "slurm" / "gallery.sbatch").string());
  ASSERT_EQ(t.exit_code, 0) << t.output;  // task 2 never runs
  const CommandResult c = shell("bash " + (out / "slurm" / "collect.sbatch").string());
  EXPECT_EQ(c.exit_code, 2) << c.output;
  EXPECT_CONTAINS(c.output, "1 of 2 scenes rendered");
  EXPECT_CONTAINS(c.output, "sbatch --array=2 " + fs::absolute(out / "slurm" / "gallery.sbatch").string());
  EXPECT_CONTAINS(file_bytes(out / "README.md"), "**Failed:** no result");
}

// The word in single quotes for /bin/sh (a line break inside stays part of the word).
std::string sh_quoted(const std::string& word) {
  std::string out = "'";
  for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// An output folder whose name carries a line break and a command: each command that writes a
// Slurm script refuses it naming the path, writes nothing, and the command never runs.
TEST_F(SlurmScripts, APathWithALineBreakIsRefusedBySweepRenderAndGallery) {
  const fs::path scene = write_scene("tiny.json", tiny_scene());
  const fs::path states = m_dir / "states";
  ASSERT_EQ(run_weft("run " + scene.string() + " --save-states --out " + states.string()).exit_code, 0);
  fs::create_directories(m_dir / "scenes");
  std::ofstream(m_dir / "scenes" / "a.json") << tiny_scene();
  const std::string evil = (m_dir / "x\ntouch PWNED\n").string();
  const std::vector<std::string> commands = {
      "sweep " + scene.string() + kSweep + " --slurm --dry-run --out " + sh_quoted(evil),
      "render " + states.string() + " --slurm --dry-run --out " + sh_quoted(evil),
      "gallery --scenes " + (m_dir / "scenes").string() + " --slurm --dry-run --out " + sh_quoted(evil)};
  for (const std::string& command : commands) {
    const CommandResult r = run_weft(command);
    EXPECT_EQ(r.exit_code, 1) << command << "\n" << r.output;
    EXPECT_CONTAINS(r.output, "x\\ntouch PWNED\\n");
    EXPECT_CONTAINS(r.output, "a Slurm script cannot name a path or value with a line break");
    EXPECT_FALSE(fs::exists(evil)) << command << ": nothing written";
  }
}

// sbatch reads a directive's value up to a space or '#', and expands '%' in --output: a folder
// with a space, '#', '"' and '%' is written quoted, with '%' doubled in the log's name.
TEST_F(SlurmScripts, DirectiveValuesAreQuoted) {
  const fs::path scene = write_scene("tiny.json", tiny_scene());
  const fs::path out = m_dir / "a b#c\"d%e";
  const CommandResult r = run_weft("sweep " + scene.string() + kSweep + " --slurm --dry-run --out " +
                                   sh_quoted(out.string()));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string log = fs::absolute(out).string();
  std::string escaped;
  for (char c : log) escaped += c == '"' ? std::string("\\\"") : c == '%' ? std::string("%%") : std::string(1, c);
  EXPECT_CONTAINS(r.output, "#SBATCH --output=\"" + escaped + "/slurm/weft-sweep_%a.log\"\n");
  EXPECT_CONTAINS(r.output, "#SBATCH --job-name=\"weft-sweep\"\n");
}

// A sweep of more points than a Slurm array holds (or than one sweep may have) is refused at
// once, before a scene is read: 10⁶ points used to read scenes for minutes, writing nothing.
TEST_F(SlurmScripts, ASweepLargerThanAnArrayIsRefusedAtOnce) {
  const fs::path scene = write_scene("tiny.json", tiny_scene());
  const auto values = [](int n) {
    std::string list;
    for (int k = 1; k <= n; ++k) list += (k > 1 ? "," : "") + std::to_string(k);
    return list;
  };
  const fs::path out = m_dir / "sweep";
  const CommandResult slurm = run_weft("sweep " + scene.string() + " --set output.frames=" + values(11) +
                                       " --set output.fps=" + values(100) + " --slurm --dry-run --out " +
                                       out.string());
  EXPECT_EQ(slurm.exit_code, 1) << slurm.output;
  EXPECT_CONTAINS(slurm.output, "--set: 11 x 100 values make more than 1000 points, more than a "
                                "Slurm array holds");
  const CommandResult local = run_weft("sweep " + scene.string() + " --set output.frames=" +
                                       values(1000) + " --set output.fps=" + values(1000) +
                                       " --out " + out.string());
  EXPECT_EQ(local.exit_code, 1) << local.output;
  EXPECT_CONTAINS(local.output, "more than 10000 points, the limit of one sweep");
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
