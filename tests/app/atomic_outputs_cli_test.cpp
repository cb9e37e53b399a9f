// Atomic outputs for every command, through the real `weft`: turntable, measure, sweep, gallery
// and run --export-meshes touch their output folder only when their first output is ready (a
// command that fails before leaves an earlier run's files byte for byte), write each file whole
// (NAME.partial, then renamed: none is left), and a run killed midway leaves only whole files.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>

#include "render/image.h"
#include "tests/app/cli_test_support.h"

namespace fs = std::filesystem;

namespace {

using weft::app::test::CommandResult;
using weft::app::test::file_bytes;
using weft::app::test::partial_names;
using weft::app::test::run_weft;
using weft::app::test::tiny_scene;

// Every file under `dir` (recursively), by its path relative to `dir`, with its bytes.
std::map<std::string, std::string> folder_bytes(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.is_regular_file())
      files[fs::relative(entry.path(), dir).string()] = file_bytes(entry.path());
  return files;
}

class AtomicOutputs : public weft::app::test::CliDirectoryTest {
 protected:
  AtomicOutputs() : CliDirectoryTest("atomic_outputs") {}
  // tiny_scene() with a time step about 80× the critical one and 2 fps: diverges in frame 1.
  fs::path diverging_scene() const {
    std::string bad = tiny_scene("", ",\n  \"simulation\": {\"time_step\": \"0.1 s\"}");
    bad.replace(bad.find("\"fps\": 24"), 9, "\"fps\": 2");
    return write_scene("diverges.json", bad);
  }
  fs::path good_scene() const { return write_scene("tiny.json", tiny_scene()); }
};

// --- a command that fails before its first output leaves the earlier run as it was ----------

TEST_F(AtomicOutputs, AMeasureThatDivergesInItsFirstFrameLeavesTheEarlierRunAsItWas) {
  const fs::path out = m_dir / "out";
  const CommandResult first = run_weft("measure " + good_scene().string() + " --out " + out.string());
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const auto before = folder_bytes(out);
  ASSERT_EQ(before.count("measure.csv"), 1u);
  ASSERT_EQ(before.count("measure.txt"), 1u);

  const CommandResult bad = run_weft("measure " + diverging_scene().string() + " --out " + out.string());
  EXPECT_EQ(bad.exit_code, 3) << bad.output;
  EXPECT_CONTAINS(bad.output, "no frame was finished; " + out.string() + " is as it was");
  EXPECT_TRUE(folder_bytes(out) == before) << "the earlier measure's files changed";
  EXPECT_FALSE(fs::exists(m_dir / "fresh"));
  const CommandResult fresh =
      run_weft("measure " + diverging_scene().string() + " --out " + (m_dir / "fresh").string());
  EXPECT_EQ(fresh.exit_code, 3) << fresh.output;
  EXPECT_FALSE(fs::exists(m_dir / "fresh")) << "a measure with nothing to write made its folder";
}

TEST_F(AtomicOutputs, ATurntableThatFailsBeforeItsFirstImageLeavesTheEarlierRunAsItWas) {
  const fs::path out = m_dir / "out";
  const CommandResult first = run_weft("turntable " + good_scene().string() +
                                       " --frames 3 --out " + out.string());
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const auto before = folder_bytes(out);
  ASSERT_EQ(before.count("turntable_0003.png"), 1u);

  const CommandResult bad = run_weft("turntable " + diverging_scene().string() +
                                     " --frames 2 --out " + out.string());
  EXPECT_EQ(bad.exit_code, 3) << bad.output;
  EXPECT_TRUE(folder_bytes(out) == before) << "the earlier turntable's files changed";

  // A turntable of fewer images replaces the earlier one's, and says so.
  const CommandResult fewer = run_weft("turntable " + good_scene().string() +
                                       " --frames 2 --out " + out.string());
  ASSERT_EQ(fewer.exit_code, 0) << fewer.output;
  EXPECT_CONTAINS(fewer.output, "replaced 3 files of an earlier run in " + out.string());
  EXPECT_TRUE(fs::exists(out / "turntable_0002.png"));
  EXPECT_FALSE(fs::exists(out / "turntable_0003.png"));
}

// --- every file whole, no .partial left ---------------------------------------------------

TEST_F(AtomicOutputs, ExportedMeshesAreWholeWithTheirCompanionsAndReplacedWhole) {
  const fs::path obj = m_dir / "obj";
  const CommandResult r =
      run_weft("run " + good_scene().string() + " --export-meshes obj --out " + obj.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(partial_names(obj).empty()) << partial_names(obj).front();
  for (int frame = 1; frame <= 4; ++frame) {
    const std::string stem = "mesh_000" + std::to_string(frame);
    const std::string text = file_bytes(obj / (stem + ".obj"));
    EXPECT_CONTAINS(text, "mtllib " + stem + ".mtl");  // the companion, by its final name
    EXPECT_TRUE(fs::exists(obj / (stem + ".mtl"))) << stem;
    // 9×9 vertices, 8×8 quads of two triangles: the whole mesh, its last face included.
    const std::regex face(R"(\nf [^\n]*)");
    EXPECT_EQ(std::distance(std::sregex_iterator(text.begin(), text.end(), face),
                            std::sregex_iterator()),
              128)
        << stem;
  }
  // A shorter run replaces every earlier mesh file, companions included.
  const CommandResult again =
      run_weft("run " + good_scene().string() + " --frames 1 --out " + obj.string());
  ASSERT_EQ(again.exit_code, 0) << again.output;
  for (const char* name : {"mesh_0001.obj", "mesh_0001.mtl", "mesh_0004.obj", "mesh_0004.mtl"})
    EXPECT_FALSE(fs::exists(obj / name)) << name;

  const fs::path gltf = m_dir / "gltf";
  const CommandResult g = run_weft("run " + good_scene().string() +
                                   " --frames 1 --export-meshes gltf --out " + gltf.string());
  ASSERT_EQ(g.exit_code, 0) << g.output;
  EXPECT_TRUE(partial_names(gltf).empty()) << partial_names(gltf).front();
  EXPECT_CONTAINS(file_bytes(gltf / "mesh_0001.gltf"), "\"mesh_0001.bin\"");
  // 81 vertices × (position, normal: 3 floats; UV: 2) + 128 × 3 indices, at least.
  EXPECT_GE(fs::file_size(gltf / "mesh_0001.bin"), 81u * 8u * 4u + 128u * 3u * 2u);
}

TEST_F(AtomicOutputs, MeasureSweepAndGalleryLeaveNoPartialFiles) {
  const fs::path measure = m_dir / "measure";
  const CommandResult m = run_weft("measure " + good_scene().string() + " --out " + measure.string());
  ASSERT_EQ(m.exit_code, 0) << m.output;
  EXPECT_TRUE(partial_names(measure).empty()) << partial_names(measure).front();
  std::istringstream csv(file_bytes(measure / "measure.csv"));
  int lines = 0;
  for (std::string line; std::getline(csv, line); ++lines)
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), 5) << line;
  EXPECT_EQ(lines, 1 + 5);  // the header, frame 0 and the 4 frames
  EXPECT_CONTAINS(file_bytes(measure / "measure.txt"), "command: ");

  const fs::path sweep = m_dir / "sweep";
  const CommandResult s = run_weft("sweep " + good_scene().string() +
                                   " --set 'cloth.resolution=[5,5],[7,7]' --frames 1 --out " +
                                   sweep.string());
  ASSERT_EQ(s.exit_code, 0) << s.output;
  EXPECT_TRUE(partial_names(sweep).empty()) << partial_names(sweep).front();
  for (const char* name : {"sweep.csv", "sweep.png", "scene.json", "run.txt"})
    EXPECT_GT(fs::file_size(sweep / name), 0u) << name;

  fs::create_directories(m_dir / "scenes");
  std::ofstream(m_dir / "scenes" / "tiny.json") << tiny_scene();
  const fs::path gallery = m_dir / "gallery";
  const CommandResult g = run_weft("gallery --scenes " + (m_dir / "scenes").string() +
                                   " --frames-scale 0.5 --out " + gallery.string());
  ASSERT_EQ(g.exit_code, 0) << g.output;
  EXPECT_TRUE(partial_names(gallery).empty()) << partial_names(gallery).front();
  EXPECT_EQ(weft::render::read_image(gallery / "tiny.png").width(), 96);
  EXPECT_CONTAINS(file_bytes(gallery / "README.md"), "## tiny");
}

// A turntable killed (SIGKILL, 4 s in) while it writes its images leaves only whole ones: every
// turntable_NNNN.png there reads as a 96×64 image.
TEST_F(AtomicOutputs, AKilledTurntableLeavesOnlyWholeImages) {
  const fs::path out = m_dir / "out";
  const CommandResult killed = run_weft("turntable " + good_scene().string() +
                                        " --frames 3600 --out " + out.string(),
                                        "timeout -s KILL 4");
  ASSERT_EQ(killed.exit_code, 128 + 9) << "not killed: " << killed.output;
  int images = 0;
  if (fs::exists(out))
    for (const auto& entry : fs::directory_iterator(out)) {
      const std::string name = entry.path().filename().string();
      if (!std::regex_match(name, std::regex(R"(turntable_\d{4}\.png)"))) continue;
      const weft::render::Image image = weft::render::read_image(entry.path());
      EXPECT_EQ(image.width(), 96) << name;
      EXPECT_EQ(image.height(), 64) << name;
      ++images;
    }
  EXPECT_GT(images, 0) << "killed before its first image: " << killed.output;
  std::printf("killed after %d whole images\n", images);
}

}  // namespace
