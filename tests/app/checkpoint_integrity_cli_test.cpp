// Checkpoints that must not resume, through the real `weft`: a checkpoint with any changed byte
// (its payload's hash is in its header), one whose scene reads an input file that changed since
// (each input file's bytes are hashed into it), and another run's checkpoint copied into a
// folder. Each is refused with exit code 1 naming the file; nothing is resumed.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/app/cli_test_support.h"

namespace fs = std::filesystem;

namespace {

using weft::app::test::CommandResult;
using weft::app::test::file_bytes;
using weft::app::test::run_weft;
using weft::app::test::tiny_scene;

class CheckpointIntegrity : public weft::app::test::CliDirectoryTest {
 protected:
  CheckpointIntegrity() : CliDirectoryTest("checkpoint_integrity") {}
  // Runs `scene` for 8 frames with a checkpoint every 4 into `out`; the checkpoint's bytes.
  std::string checkpointed_run(const fs::path& scene, const fs::path& out) const {
    const CommandResult r = run_weft("run " + scene.string() + " --frames 8 --checkpoint-every 4 --out " +
                                     out.string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return file_bytes(out / "checkpoint.weft");
  }
};

// One flipped bit anywhere after the header — in the scene text, the stats rows, a position —
// used to resume with exit 0 and other frames for 22 of 40 such files.
TEST_F(CheckpointIntegrity, ACheckpointWithAnyChangedByteIsRefused) {
  const fs::path out = m_dir / "out";
  const std::string good = checkpointed_run(write_scene("tiny.json", tiny_scene()), out);
  const std::size_t header = std::string("weft checkpoint 3\n").size() + 24;
  ASSERT_GT(good.size(), header + 100);
  const fs::path file = out / "checkpoint.weft";
  for (int k = 0; k < 24; ++k) {
    const std::size_t at = header + (good.size() - header - 1) * static_cast<std::size_t>(k) / 23;
    std::string bad = good;
    bad[at] = static_cast<char>(bad[at] ^ 0x10);
    std::ofstream(file, std::ios::binary) << bad;
    const CommandResult r = run_weft("run --resume " + out.string());
    EXPECT_EQ(r.exit_code, 1) << "byte " << at << "\n" << r.output;
    EXPECT_CONTAINS(r.output, file.string() + ": its content does not match the hash in its header");
  }
  std::ofstream(file, std::ios::binary) << good;
  EXPECT_EQ(run_weft("run --resume " + out.string()).exit_code, 0);
}

TEST_F(CheckpointIntegrity, AnInputFileChangedSinceTheCheckpointIsRefusedNamingIt) {
  const std::string pyramid = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nv 0 0 -1\n"
                              "f 1 2 3\nf 1 3 4\nf 1 5 2\nf 2 5 3\nf 3 5 4\nf 4 5 1\n";
  std::ofstream(m_dir / "panel.obj") << pyramid;
  const fs::path scene = write_scene(
      "obstacle.json", tiny_scene("", ",\n  \"obstacles\": [{\"mesh\": {\"file\": \"panel.obj\", "
                                      "\"scale\": 0.05, \"translate\": [0, 0, 0.2]}}]"));
  const fs::path out = m_dir / "out";
  checkpointed_run(scene, out);
  std::ofstream(m_dir / "panel.obj") << "v -1 -1 0.01\n" << pyramid.substr(pyramid.find('\n') + 1);
  const CommandResult r = run_weft("run --resume " + out.string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_CONTAINS(r.output, (m_dir / "panel.obj").string() + ": not the file the checkpointed run read");
  std::ofstream(m_dir / "panel.obj") << pyramid;
  const CommandResult again = run_weft("run --resume " + out.string());
  EXPECT_EQ(again.exit_code, 0) << again.output;
}

// Scene A's frames 1–8, then B's checkpoint copied in: resuming would mix the two scenes.
TEST_F(CheckpointIntegrity, AnotherRunsCheckpointCopiedIntoAFolderIsRefused) {
  const fs::path a = m_dir / "a", b = m_dir / "b";
  checkpointed_run(write_scene("a.json", tiny_scene()), a);
  checkpointed_run(write_scene("b.json", tiny_scene("", R"(, "simulation": {"integrator": "implicit_euler"})")), b);
  fs::copy_file(b / "checkpoint.weft", a / "checkpoint.weft", fs::copy_options::overwrite_existing);
  const std::string frame = file_bytes(a / "frame_0008.png");
  const CommandResult r = run_weft("run --resume " + a.string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_CONTAINS(r.output, "the checkpoint's scene is not " + (a / "scene.json").string());
  EXPECT_EQ(file_bytes(a / "frame_0008.png"), frame);
}

}  // namespace
