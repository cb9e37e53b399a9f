// Slurm jobs on a real Slurm: scripts/slurm-local starts a one-node cluster (munge,
// slurmctld, slurmd) and `weft render --slurm` submits a ray-traced 12-frame sequence as 4
// array tasks; the frames equal those weft run wrote, byte for byte. `weft sweep --slurm` (6
// points) and `weft gallery --slurm` (2 scenes) give the local sweep's and gallery's bytes
// through their collect jobs, and a failing point is listed while the others merge. Skipped, saying why, where
// the cluster cannot start (slurm-wlm or munge missing, not root).
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>

#include "tests/app/slurm_test_support.h"

namespace fs = std::filesystem;

namespace {

using weft::app::test::file_bytes;
using weft::app::test::run_weft;
using weft::app::test::tiny_scene;

using weft::app::test::shell;

// The job sbatch submitted last (a sweep's or gallery's collect job).
std::string last_job(const std::string& sbatch_output) {
  const std::size_t at = sbatch_output.rfind("Submitted batch job ");
  return at == std::string::npos ? "" : std::to_string(std::stol(sbatch_output.substr(at + 20)));
}

class SlurmCli : public ::testing::Test {
 protected:
  void SetUp() override {
    m_dir = weft::app::test::fresh_test_directory("slurm_cli");
    m_state = m_dir / "cluster";
    // Ports of this test run's own, so that clusters of runs at once do not meet.
    const std::string port = std::to_string(20000 + 2 * (getpid() % 10000));
    const auto started = shell("SLURM_LOCAL_PORT=" + port + " " + WEFT_SOURCE_DIR +
                               "/scripts/slurm-local start " + m_state.string());
    if (started.exit_code == 77) GTEST_SKIP() << started.output;
    ASSERT_EQ(started.exit_code, 0) << started.output;
    m_env = "SLURM_CONF=" + (m_state / "slurm.conf").string();
  }
  void TearDown() override {
    if (!m_env.empty()) shell(std::string(WEFT_SOURCE_DIR) + "/scripts/slurm-local stop " + m_state.string());
  }
  // Waits (up to two minutes) until the job has left the queue.
  void wait_for(const std::string& job) {
    ASSERT_FALSE(job.empty()) << "no job submitted";
    for (int i = 0; i < 1200; ++i) {
      if (shell(m_env + " squeue -h -j " + job).output.find(job) == std::string::npos) return;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    FAIL() << "job " << job << " still queued after two minutes";
  }
  fs::path m_dir, m_state;
  std::string m_env;
};

TEST_F(SlurmCli, ARayTracedSequenceAsFourArrayTasksEqualsTheSingleRunsFrames) {
  const fs::path scene = m_dir / "tiny.json";
  std::ofstream(scene) << tiny_scene();
  const fs::path states = m_dir / "run", out = m_dir / "tasks";
  const std::string raytrace = " --renderer raytrace --samples 2";
  const auto run = run_weft("run " + scene.string() + " --frames 12 --save-states" + raytrace +
                            " --out " + states.string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto submitted = run_weft("render " + states.string() + raytrace +
                                  " --slurm --tasks 4 --out " + out.string(), m_env);
  ASSERT_EQ(submitted.exit_code, 0) << submitted.output;
  const std::size_t at = submitted.output.find("Submitted batch job ");
  ASSERT_NE(at, std::string::npos) << submitted.output;
  const std::string job = std::to_string(std::stol(submitted.output.substr(at + 20)));
  wait_for(job);
  for (int task = 1; task <= 4; ++task)  // numbered from 1, as sweep and gallery tasks
    EXPECT_TRUE(fs::exists(out / "slurm" / ("weft-render_" + std::to_string(task) + ".log"))) << task;
  for (int k = 1; k <= 12; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04d.png", k);
    ASSERT_TRUE(fs::exists(out / name)) << name;
    EXPECT_TRUE(file_bytes(states / name) == file_bytes(out / name)) << name << " differs";
  }
}

TEST_F(SlurmCli, ASixPointSweepAsArrayTasksMergesIntoTheLocalSweepsBytes) {
  const fs::path scene = m_dir / "tiny.json";
  std::ofstream(scene) << tiny_scene();
  const fs::path local = m_dir / "local", tasks = m_dir / "tasks";
  const std::string sweep = "sweep " + scene.string() + weft::app::test::kSixPointSweep;
  const auto l = run_weft(sweep + " --out " + local.string(), weft::app::test::kModelWallTime);
  ASSERT_EQ(l.exit_code, 0) << l.output;
  const auto submitted = run_weft(sweep + " --out " + tasks.string() + " --slurm",
                                  m_env + " " + weft::app::test::kModelWallTime);
  ASSERT_EQ(submitted.exit_code, 0) << submitted.output;
  wait_for(last_job(submitted.output));
  const std::string log = file_bytes(tasks / "slurm" / "weft-sweep-collect.log");
  ASSERT_TRUE(fs::exists(tasks / "sweep.csv")) << log;
  EXPECT_EQ(file_bytes(local / "sweep.csv"), file_bytes(tasks / "sweep.csv"));
  EXPECT_TRUE(file_bytes(local / "sweep.png") == file_bytes(tasks / "sweep.png")) << "plots differ";
  EXPECT_NE(log.find("Pareto-optimal settings"), std::string::npos) << log;
  for (int k = 1; k <= 6; ++k)
    EXPECT_TRUE(fs::exists(tasks / "slurm" / ("weft-sweep_" + std::to_string(k) + ".log"))) << k;
}

TEST_F(SlurmCli, AFailingSweepPointIsListedAndTheOthersMerge) {
  const fs::path scene = m_dir / "tiny.json";
  std::ofstream(scene) << tiny_scene();
  const fs::path local = m_dir / "local", tasks = m_dir / "tasks";
  // Real wall times here; --reference: the errors are against the same run whatever they are.
  const std::string sweep =
      "sweep " + scene.string() + weft::app::test::kSixPointSweep + " --reference 5";
  const auto l = run_weft(sweep + " --out " + local.string());
  ASSERT_EQ(l.exit_code, 0) << l.output;
  const auto submitted =
      run_weft(sweep + " --out " + tasks.string() + " --slurm", m_env + " WEFT_SWEEP_FAIL_RUNS=3");
  ASSERT_EQ(submitted.exit_code, 0) << submitted.output;
  wait_for(last_job(submitted.output));
  const std::string log = file_bytes(tasks / "slurm" / "weft-sweep-collect.log");
  EXPECT_NE(log.find("run 3 (cloth.resolution=[7,7] simulation.integrator=symplectic_euler) failed"),
            std::string::npos) << log;
  EXPECT_NE(log.find("sbatch --array=3 " + fs::absolute(tasks / "slurm" / "sweep.sbatch").string()),
            std::string::npos) << log;
  EXPECT_NE(file_bytes(tasks / "slurm" / "weft-sweep_3.log").find("failing on purpose"),
            std::string::npos);
  weft::app::test::expect_same_sweep_rows(local / "sweep.csv", tasks / "sweep.csv", 3);
}

TEST_F(SlurmCli, AGalleryAsArrayTasksEqualsTheLocalGallery) {
  fs::create_directories(m_dir / "scenes");
  std::ofstream(m_dir / "scenes" / "a.json") << tiny_scene();
  std::ofstream(m_dir / "scenes" / "b.json")
      << tiny_scene("", R"(, "simulation": {"integrator": "implicit_euler"})");
  const std::string gallery = "gallery --scenes " + (m_dir / "scenes").string() + " --out " +
                              (m_dir / "gallery").string();
  const auto l = run_weft(gallery);
  ASSERT_EQ(l.exit_code, 0) << l.output;
  fs::rename(m_dir / "gallery", m_dir / "local");  // README.md names --out: the same for both
  const auto submitted = run_weft(gallery + " --slurm", m_env);
  ASSERT_EQ(submitted.exit_code, 0) << submitted.output;
  wait_for(last_job(submitted.output));
  const fs::path out = m_dir / "gallery";
  for (const char* name : {"a.png", "a_sheet.png", "b.png", "b_sheet.png"})
    EXPECT_TRUE(file_bytes(m_dir / "local" / name) == file_bytes(out / name)) << name << " differs";
  std::string readme = file_bytes(out / "README.md");
  const std::size_t flag = readme.find(" --slurm");
  ASSERT_NE(flag, std::string::npos) << readme;  // the command the user gave
  readme.erase(flag, 8);
  EXPECT_EQ(readme, file_bytes(m_dir / "local" / "README.md"));
}

}  // namespace
