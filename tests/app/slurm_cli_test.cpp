// Issue 22 items 3 and 4 on a real Slurm: scripts/slurm-local starts a one-node cluster (munge,
// slurmctld, slurmd) and `weft render --slurm` submits a ray-traced 12-frame sequence as 4
// array tasks; the frames equal those weft run wrote, byte for byte. Skipped, saying why, where
// the cluster cannot start (slurm-wlm or munge missing, not root).
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>

#include "tests/app/cli_test_support.h"

namespace fs = std::filesystem;

namespace {

using weft::app::test::file_bytes;
using weft::app::test::run_weft;
using weft::app::test::tiny_scene;

// The output of a shell command and its exit code.
weft::app::test::CommandResult shell(const std::string& command) {
  weft::app::test::CommandResult r;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  char buffer[512];
  while (pipe && fgets(buffer, sizeof buffer, pipe)) r.output += buffer;
  const int status = pipe ? pclose(pipe) : -1;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
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
  // Waits (up to a minute) until the job has left the queue.
  void wait_for(const std::string& job) {
    for (int i = 0; i < 600; ++i) {
      if (shell(m_env + " squeue -h -j " + job).output.find(job) == std::string::npos) return;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    FAIL() << "job " << job << " still queued after a minute";
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
  for (int task = 0; task < 4; ++task)
    EXPECT_TRUE(fs::exists(out / "slurm" / ("weft-render_" + std::to_string(task) + ".log"))) << task;
  for (int k = 1; k <= 12; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04d.png", k);
    ASSERT_TRUE(fs::exists(out / name)) << name;
    EXPECT_TRUE(file_bytes(states / name) == file_bytes(out / name)) << name << " differs";
  }
}

}  // namespace
