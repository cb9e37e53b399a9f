// Output folders others can write into, through the real `weft`: a symbolic link planted at a
// temporary name (NAME.partial) is never written through, and a full disk leaves no partial file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/app/cli_test_support.h"

namespace fs = std::filesystem;

namespace {

using weft::app::test::CommandResult;
using weft::app::test::file_bytes;
using weft::app::test::run_weft;
using weft::app::test::tiny_scene;

// The names under `dir` that end in ".partial" (files, folders or links).
std::vector<std::string> partial_names(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.path().extension() == ".partial") names.push_back(entry.path().string());
  return names;
}

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

}  // namespace
