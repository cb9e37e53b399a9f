// Output folders others can write into, and outputs that must never replace inputs, through
// the real `weft`: a symbolic link planted at a temporary name (NAME.partial) is never written
// through, a full disk leaves no partial file, two runs into one folder are refused, and no
// command deletes or overwrites a file it reads.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/app/cli_test_support.h"

namespace fs = std::filesystem;

namespace {

using weft::app::test::CommandResult;
using weft::app::test::file_bytes;
using weft::app::test::partial_names;
using weft::app::test::run_weft;
using weft::app::test::tiny_scene;

class SharedFolder : public weft::app::test::CliDirectoryTest {
 protected:
  SharedFolder() : CliDirectoryTest("shared_folder") {}
  fs::path good_scene() const { return write_scene("tiny.json", tiny_scene()); }
  // A file outside the output folder that a planted link points to.
  fs::path victim(const std::string& name) const {
    const fs::path path = m_dir / "victims" / name;
    fs::create_directories(path.parent_path());
    std::ofstream(path) << "precious " << name << "\n";
    return path;
  }
};

// --- symbolic links at the temporary names ----------------------------------------------------

TEST_F(SharedFolder, ALinkPlantedAtATemporaryNameIsNotWrittenThrough) {
  const fs::path out = m_dir / "out";
  fs::create_directories(out);
  const std::vector<std::string> names = {
      "stats.csv.partial",      "scene.json.partial",      "run.txt.partial",
      "frame_0001.png.partial", "checkpoint.weft.partial", "state_0001.npy.partial"};
  for (const std::string& name : names) fs::create_symlink(victim(name), out / name);
  // assimp's folder for an exported mesh: a link to a folder must not receive the mesh.
  fs::create_directories(m_dir / "victim_folder");
  fs::create_directory_symlink(m_dir / "victim_folder", out / "mesh_0001.obj.partial");

  const CommandResult r = run_weft("run " + good_scene().string() +
                                   " --checkpoint-every 1 --save-states --export-meshes obj --out " +
                                   out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const std::string& name : names)
    EXPECT_EQ(file_bytes(m_dir / "victims" / name), "precious " + name + "\n") << name;
  EXPECT_TRUE(fs::is_empty(m_dir / "victim_folder"));
  EXPECT_TRUE(partial_names(out).empty());
  for (const char* name : {"stats.csv", "scene.json", "frame_0001.png", "checkpoint.weft",
                           "state_0001.npy", "mesh_0001.obj"})
    EXPECT_TRUE(fs::is_regular_file(out / name)) << name;
}

// --- a full disk ------------------------------------------------------------------------------

// A file size limit (ulimit -f, with SIGXFSZ ignored so that a write fails with EFBIG as on a
// full disk): the run fails naming the file, and no partial file is left.
TEST_F(SharedFolder, AFullDiskLeavesNoPartialFile) {
  const fs::path out = m_dir / "out";
  const CommandResult r = run_weft("run " + good_scene().string() + " --size 400x300 --out " +
                                       out.string(),
                                   "ulimit -f 4; trap '' XFSZ;");
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_CONTAINS(r.output, "File too large");
  ASSERT_TRUE(fs::exists(out)) << r.output;
  EXPECT_TRUE(partial_names(out).empty());
}

// --- two commands into one folder -------------------------------------------------------------

// The lock another weft command would hold: flock on OUT/.weft-lock, taken here.
class HeldLock {
 public:
  explicit HeldLock(const fs::path& dir) {
    fs::create_directories(dir);
    m_fd = ::open((dir / ".weft-lock").c_str(), O_RDWR | O_CREAT, 0666);
    EXPECT_EQ(::flock(m_fd, LOCK_EX | LOCK_NB), 0);
  }
  ~HeldLock() { ::close(m_fd); }

 private:
  int m_fd = -1;
};

TEST_F(SharedFolder, ACommandIntoAFolderAnotherIsWritingIsRefusedAndRemovesNothing) {
  const fs::path out = m_dir / "out";
  ASSERT_EQ(run_weft("run " + good_scene().string() + " --out " + out.string()).exit_code, 0);
  const std::string frame = file_bytes(out / "frame_0004.png");
  {
    const HeldLock other(out);
    for (const std::string& command :
         {"run " + good_scene().string() + " --frames 2", "measure " + good_scene().string(),
          "turntable " + good_scene().string() + " --frames 2"}) {
      const CommandResult r = run_weft(command + " --out " + out.string());
      EXPECT_EQ(r.exit_code, 1) << command << "\n" << r.output;
      EXPECT_CONTAINS(r.output, out.string() + ": another weft command is writing into this folder");
      EXPECT_EQ(file_bytes(out / "frame_0004.png"), frame) << command;
    }
  }
  const CommandResult after = run_weft("run " + good_scene().string() + " --frames 2 --out " + out.string());
  EXPECT_EQ(after.exit_code, 0) << after.output;  // the lock ends with its holder
  EXPECT_FALSE(fs::exists(out / "frame_0004.png"));
}

TEST_F(SharedFolder, AResumeIntoAFolderAnotherIsWritingIsRefused) {
  const fs::path out = m_dir / "out";
  ASSERT_EQ(run_weft("run " + good_scene().string() + " --checkpoint-every 2 --out " + out.string()).exit_code, 0);
  const HeldLock other(out);
  const CommandResult r = run_weft("run --resume " + out.string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_CONTAINS(r.output, "another weft command is writing into this folder");
}

// --- no output replaces an input ---------------------------------------------------------------

TEST_F(SharedFolder, ARunRefusesToOverwriteItsSceneFile) {
  const fs::path scene = write_scene("scene.json", tiny_scene());
  const std::string before = file_bytes(scene);
  // The folder as given, and another path to it.
  for (const fs::path& out : {m_dir, m_dir / "." / ""}) {
    const CommandResult r = run_weft("run " + scene.string() + " --frames 2 --out " + out.string());
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_CONTAINS(r.output, scene.string() + ": an input of this command, but the output folder");
    EXPECT_CONTAINS(r.output, "is where it writes (or removes an earlier run's) scene.json");
    EXPECT_EQ(file_bytes(scene), before);
    EXPECT_FALSE(fs::exists(m_dir / "frame_0001.png"));
  }
  // Another name in the folder is no output: the run goes on.
  fs::rename(scene, m_dir / "tiny.json");
  EXPECT_EQ(run_weft("run " + (m_dir / "tiny.json").string() + " --frames 1 --out " + m_dir.string())
                .exit_code, 0);
  EXPECT_EQ(file_bytes(m_dir / "tiny.json"), before);
}

TEST_F(SharedFolder, AnObstacleMeshNamedLikeAnOutputFrameIsNotDeleted) {
  const fs::path out = m_dir / "out";
  fs::create_directories(out);
  std::ofstream(out / "mesh_0001.obj") << "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nv 0 0 -1\n"
                                          "f 1 2 3\nf 1 3 4\nf 1 5 2\nf 2 5 3\nf 3 5 4\nf 4 5 1\n";
  const std::string mesh = file_bytes(out / "mesh_0001.obj");
  const fs::path scene = write_scene(
      "obstacle.json",
      tiny_scene("", ",\n  \"obstacles\": [{\"mesh\": {\"file\": \"out/mesh_0001.obj\", "
                     "\"scale\": 0.05, \"translate\": [0, 0, 0.2]}}]"));
  const CommandResult r = run_weft("run " + scene.string() + " --out " + out.string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_CONTAINS(r.output, "mesh_0001.obj: an input of this command");
  EXPECT_CONTAINS(r.output, "mesh_NNNN.(obj|mtl|ply|gltf|bin)");
  EXPECT_EQ(file_bytes(out / "mesh_0001.obj"), mesh);
}

TEST_F(SharedFolder, CompareRefusesToOverwriteItsInputs) {
  const fs::path out = m_dir / "out";
  ASSERT_EQ(run_weft("run " + good_scene().string() + " --frames 1 --out " + out.string()).exit_code, 0);
  fs::copy_file(out / "frame_0001.png", out / "photo.png");
  const std::string photo = file_bytes(out / "photo.png");
  const CommandResult r = run_weft("compare " + (out / "photo.png").string() + " " +
                                   (out / "frame_0001.png").string() + " --out " + out.string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_CONTAINS(r.output, (out / "photo.png").string() + ": an input of this command");
  EXPECT_EQ(file_bytes(out / "photo.png"), photo);
  EXPECT_FALSE(fs::exists(out / "report.html"));
}

// A fit file kept in the folder its results go to, under the name of one of them.
TEST_F(SharedFolder, FitRefusesToOverwriteItsFitFile) {
  const fs::path out = m_dir / "out";
  fs::create_directories(out);
  const fs::path fit = out / "fit_result.json";
  std::ofstream(fit) << R"({"description": "test", "scene": ")" << WEFT_SOURCE_DIR
                     << R"(/assets/scenes/bendstiff_strip.json", "parameters": [{"name": "bend", )"
                        R"("start": "0.05 N*m"}], "target": {"measured": {"drop": "80 mm"}}})";
  const std::string before = file_bytes(fit);
  const CommandResult r = run_weft("fit " + fit.string() + " --out " + out.string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_CONTAINS(r.output, fit.string() + ": an input of this command");
  EXPECT_EQ(file_bytes(fit), before);
  EXPECT_FALSE(fs::exists(out / "fit.csv"));
}

}  // namespace
