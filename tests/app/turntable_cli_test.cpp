// End to end through the real `weft turntable` (and `weft run --export-meshes`): a tiny scene
// and the icosphere mesh give N frames seen from N directions and a contact sheet; without
// ffmpeg a clear note, with it the mp4 and gif (a stand-in ffmpeg checks the call and the exit
// status); bad input is an error naming its cause, exit code 1, nothing written.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "render/image.h"
#include "tests/app/cli_test_support.h"

namespace fs = std::filesystem;

namespace {

using weft::app::test::CommandResult;
using weft::app::test::run_weft;
using weft::render::Image;

#define EXPECT_CONTAINS(text, part) \
  EXPECT_NE((text).find(part), std::string::npos) << "missing: " << (part) << "\nin: " << (text)

class TurntableCli : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    m_dir = fs::path(WEFT_BINARY_DIR) / "test_output" / "turntable_cli" / info->name();
    fs::remove_all(m_dir);
    fs::create_directories(m_dir);
  }
  fs::path write_file(const std::string& name, const std::string& text) const {
    const fs::path path = m_dir / name;
    std::ofstream(path) << text;
    return path;
  }
  // A PATH with only a stand-in `ffmpeg` that exits with `status` after creating its output
  // file (its last argument) — or, for status < 0, a PATH without ffmpeg.
  std::string path_env(int status) const {
    const fs::path bin = m_dir / "bin";
    fs::create_directories(bin);
    if (status >= 0) {
      const fs::path script = bin / "ffmpeg";
      std::ofstream(script) << "#!/bin/sh\nfor last; do :; done\n: > \"$last\"\necho \"$@\" >> \""
                            << (m_dir / "ffmpeg_calls.txt").string() << "\"\nexit " << status
                            << "\n";
      fs::permissions(script, fs::perms::owner_all);
    }
    return "PATH=" + bin.string();
  }
  fs::path m_dir;
};

// A 9×9 cloth pinned at two corners, 2 frames; images of 64×48 pixels.
const char* const turntable_scene = R"({
  "description": "tiny turntable test scene",
  "cloth": {"size": ["20 cm", "20 cm"], "resolution": [9, 9], "origin": [-0.1, 0, 0.5],
            "pins": [{"corner": "u0v1"}, {"corner": "u1v1"}]},
  "output": {"fps": 24, "frames": 2},
  "render": {"size": [64, 48], "camera": {"eye": [0.6, -0.5, 0.6], "target": [0, 0.1, 0.4]}}
}
)";

int differing_pixels(const Image& a, const Image& b) {
  int n = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) n += !(a.at(x, y) == b.at(x, y));
  return n;
}

TEST_F(TurntableCli, SceneGivesFourFramesFromFourSidesAndAContactSheet) {
  const fs::path scene = write_file("tiny.json", turntable_scene);
  const fs::path out = m_dir / "out";
  const CommandResult r =
      run_weft("turntable " + scene.string() + " --frames 4 --out " + out.string(), path_env(-1));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_CONTAINS(r.output, "ffmpeg not found: wrote PNGs and the contact sheet only; apt-get "
                            "install ffmpeg for mp4/gif");
  std::vector<Image> frames;
  for (int i = 1; i <= 4; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "turntable_%04d.png", i);
    ASSERT_TRUE(fs::exists(out / name)) << name;
    frames.push_back(weft::render::read_image(out / name));
    EXPECT_EQ(frames.back().width(), 64);
    EXPECT_EQ(frames.back().height(), 48);
  }
  EXPECT_FALSE(fs::exists(out / "turntable_0005.png"));
  // Image k at azimuth 360 (k − 1) / N, as --help says.
  EXPECT_CONTAINS(r.output, "frame 1/4  azimuth 0 deg");
  EXPECT_CONTAINS(r.output, "frame 4/4  azimuth 270 deg");
  EXPECT_CONTAINS(run_weft("turntable --help").output,
                  "turntable_0001.png at azimuth 0 (the camera's own direction), image k at "
                  "360*(k-1)/N degrees");
  // Four different views (the cloth is seen from four sides, the light stays put).
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j)
      EXPECT_GT(differing_pixels(frames[static_cast<std::size_t>(i)],
                                 frames[static_cast<std::size_t>(j)]), 64 * 48 / 50)
          << i << " vs " << j;
  ASSERT_TRUE(fs::exists(out / "contact_sheet.png"));
  const Image sheet = weft::render::read_image(out / "contact_sheet.png");
  EXPECT_GT(sheet.width(), 2 * 64);  // 2 × 2 thumbnails of full size
  EXPECT_GT(sheet.height(), 2 * 48);
  EXPECT_TRUE(fs::exists(out / "turntable.txt"));
  EXPECT_TRUE(fs::exists(out / "scene.json"));
  EXPECT_FALSE(fs::exists(out / "turntable.mp4"));
}

TEST_F(TurntableCli, MeshFileIsFramedAndTurned) {
  const fs::path out = m_dir / "out";
  const CommandResult r = run_weft("turntable " + std::string(WEFT_SOURCE_DIR) +
                                       "/assets/meshes/icosphere_3.obj --frames 3 --size 64x48 "
                                       "--out " + out.string(),
                                   path_env(-1));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* name : {"turntable_0001.png", "turntable_0002.png", "turntable_0003.png",
                           "contact_sheet.png"})
    EXPECT_TRUE(fs::exists(out / name)) << name;
  // The sphere is framed: it covers a good part of the image and does not touch its border.
  const Image first = weft::render::read_image(out / "turntable_0001.png");
  int covered = 0;
  bool border = false;
  for (int y = 0; y < first.height(); ++y)
    for (int x = 0; x < first.width(); ++x) {
      const weft::render::Rgb8 p = first.at(x, y);
      const bool red = p.r > p.g + 40;  // the front colour
      covered += red;
      if (red && (x == 0 || y == 0 || x == first.width() - 1 || y == first.height() - 1))
        border = true;
    }
  EXPECT_GT(covered, 64 * 48 / 10);
  EXPECT_FALSE(border);
  EXPECT_FALSE(fs::exists(out / "scene.json"));
}

TEST_F(TurntableCli, FfmpegMakesTheMp4AndGifAndItsFailureIsReported) {
  const fs::path scene = write_file("tiny.json", turntable_scene);
  const fs::path out = m_dir / "out";
  const std::string args = "turntable " + scene.string() + " --frames 2 --out " + out.string();
  const CommandResult ok = run_weft(args, path_env(0));
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_TRUE(fs::exists(out / "turntable.mp4"));
  EXPECT_TRUE(fs::exists(out / "turntable.gif"));
  std::ifstream calls(m_dir / "ffmpeg_calls.txt");
  const std::string text((std::istreambuf_iterator<char>(calls)), std::istreambuf_iterator<char>());
  EXPECT_CONTAINS(text, (out / "turntable_%04d.png").string());
  EXPECT_CONTAINS(text, "libx264");
  EXPECT_CONTAINS(text, "paletteuse");
  EXPECT_CONTAINS(text, "-framerate 12 ");  // the default video rate
  EXPECT_CONTAINS(ok.output, "in all, simulation included)");
  // --video-fps sets it; a rate outside (0, 240] is refused, naming it.
  const CommandResult fast = run_weft(args + " --video-fps 30", path_env(0));
  ASSERT_EQ(fast.exit_code, 0) << fast.output;
  std::ifstream calls2(m_dir / "ffmpeg_calls.txt");
  const std::string text2((std::istreambuf_iterator<char>(calls2)), std::istreambuf_iterator<char>());
  EXPECT_CONTAINS(text2, "-framerate 30 ");
  const CommandResult bad = run_weft(args + " --video-fps 0", path_env(0));
  EXPECT_EQ(bad.exit_code, 1) << bad.output;
  EXPECT_CONTAINS(bad.output, "--video-fps");

  const CommandResult failed = run_weft(args, path_env(3));
  EXPECT_EQ(failed.exit_code, 2) << failed.output;
  EXPECT_CONTAINS(failed.output, "turntable.mp4: ffmpeg failed with exit status 3");
  EXPECT_TRUE(fs::exists(out / "contact_sheet.png"));  // kept
}

TEST_F(TurntableCli, BadInputIsAnErrorWithNothingWritten) {
  const fs::path out = m_dir / "out";
  const fs::path scene = write_file("tiny.json", turntable_scene);
  const CommandResult missing =
      run_weft("turntable " + (m_dir / "nope.json").string() + " --out " + out.string());
  EXPECT_EQ(missing.exit_code, 1) << missing.output;
  EXPECT_CONTAINS(missing.output, "nope.json: no such file");

  const CommandResult zero =
      run_weft("turntable " + scene.string() + " --frames 0 --out " + out.string());
  EXPECT_EQ(zero.exit_code, 1) << zero.output;
  EXPECT_CONTAINS(zero.output, "--frames: expected a number in [1, 3600], got '0'");

  const fs::path text = write_file("notes.txt", "hello");
  const CommandResult unknown = run_weft("turntable " + text.string() + " --out " + out.string());
  EXPECT_EQ(unknown.exit_code, 1) << unknown.output;
  EXPECT_CONTAINS(unknown.output, "notes.txt: expected a scene (.json) or a mesh file");

  const fs::path broken = write_file("broken.obj", "v 0 0 0\nf 1 2 3\n");
  const CommandResult bad_mesh = run_weft("turntable " + broken.string() + " --out " + out.string());
  EXPECT_EQ(bad_mesh.exit_code, 1) << bad_mesh.output;
  EXPECT_CONTAINS(bad_mesh.output, "broken.obj");

  const CommandResult steep = run_weft("turntable " + scene.string() +
                                       " --elevation-deg 95 --out " + out.string());
  EXPECT_EQ(steep.exit_code, 1) << steep.output;
  EXPECT_CONTAINS(steep.output, "--elevation-deg");
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(TurntableCli, RunExportsOneMeshPerFrame) {
  const fs::path scene = write_file("tiny.json", turntable_scene);
  const fs::path out = m_dir / "out";
  const CommandResult r =
      run_weft("run " + scene.string() + " --export-meshes ply --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* name : {"mesh_0001.ply", "mesh_0002.ply"}) {
    std::ifstream in(out / name);
    std::string magic;
    in >> magic;
    EXPECT_EQ(magic, "ply") << name;
  }
  // A later run in the same folder replaces the earlier run's meshes as it does its frames.
  const CommandResult again = run_weft("run " + scene.string() + " --frames 1 --out " + out.string());
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_FALSE(fs::exists(out / "mesh_0001.ply"));
  EXPECT_FALSE(fs::exists(out / "mesh_0002.ply"));
  const CommandResult bad =
      run_weft("run " + scene.string() + " --export-meshes stl --out " + (m_dir / "bad").string());
  EXPECT_EQ(bad.exit_code, 1) << bad.output;
  EXPECT_CONTAINS(bad.output, "--export-meshes");
  EXPECT_FALSE(fs::exists(m_dir / "bad"));
}

// A later run clears every file of the earlier run's meshes, the OBJs'
// mesh_NNNN.mtl included.
TEST_F(TurntableCli, ARerunLeavesNoStaleMaterialFiles) {
  const fs::path scene = write_file("tiny.json", turntable_scene);
  const fs::path out = m_dir / "out";
  const CommandResult r =
      run_weft("run " + scene.string() + " --frames 2 --export-meshes obj --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ASSERT_TRUE(fs::exists(out / "mesh_0002.mtl"));
  const CommandResult again = run_weft("run " + scene.string() + " --frames 1 --out " + out.string());
  ASSERT_EQ(again.exit_code, 0) << again.output;
  for (const fs::directory_entry& entry : fs::directory_iterator(out))
    EXPECT_NE(entry.path().filename().string().rfind("mesh_", 0), 0u) << entry.path();
  EXPECT_TRUE(fs::exists(out / "frame_0001.png"));
}

// The centre the turntable banner names: "… 1 frame around (X, Y, Z) m".
std::string orbit_centre(const std::string& output) {
  std::smatch m;
  if (!std::regex_search(output, m, std::regex(R"(1 frame around (\([^)]*\)) m)"))) return "none";
  return m[1];
}

// weft's own OBJ export is y-up by default: turntable MESH reads it back y-up (--up y, the
// default) into weft's z-up frame, so the exported last frame orbits the same centre as the
// scene's own turntable (the cloth stands; read in the file's frame it would lie on its side,
// its centre at z ≈ 0). A --up z export is read with --up z. A scene, or a glTF, refuses --up z.
TEST_F(TurntableCli, WeftsOwnExportStandsUpInTheTurntable) {
  const fs::path scene = write_file("tiny.json", turntable_scene);
  const CommandResult own = run_weft("turntable " + scene.string() + " --frames 1 --size 32x24 --out " +
                                     (m_dir / "scene_tt").string(), path_env(-1));
  ASSERT_EQ(own.exit_code, 0) << own.output;
  const std::string centre = orbit_centre(own.output);
  ASSERT_NE(centre, "none") << own.output;
  for (const char* up : {"y", "z"}) {
    const fs::path run = m_dir / (std::string("run_") + up);
    const CommandResult r = run_weft("run " + scene.string() + " --export-meshes obj --up " + up +
                                     " --out " + run.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const std::string mesh = (run / "mesh_0002.obj").string();
    const std::string as_read = up == std::string("y") ? "" : " --up z";
    const CommandResult t = run_weft("turntable " + mesh + as_read + " --frames 1 --size 32x24 --out " +
                                     (m_dir / (std::string("tt_") + up)).string(), path_env(-1));
    ASSERT_EQ(t.exit_code, 0) << t.output;
    EXPECT_EQ(orbit_centre(t.output), centre) << "exported with --up " << up << "\n" << t.output;
  }
  // Read in the wrong frame, the y-up export lies on its side: another centre.
  const CommandResult sideways = run_weft("turntable " + (m_dir / "run_y" / "mesh_0002.obj").string() +
                                          " --up z --frames 1 --size 32x24 --out " +
                                          (m_dir / "tt_sideways").string(), path_env(-1));
  ASSERT_EQ(sideways.exit_code, 0) << sideways.output;
  EXPECT_NE(orbit_centre(sideways.output), centre);

  const CommandResult on_scene = run_weft("turntable " + scene.string() + " --up y --out " +
                                          (m_dir / "bad1").string(), path_env(-1));
  EXPECT_EQ(on_scene.exit_code, 1) << on_scene.output;
  EXPECT_CONTAINS(on_scene.output, "--up: only for a mesh file");
  const CommandResult gltf_run = run_weft("run " + scene.string() + " --frames 1 --export-meshes gltf --out " +
                                          (m_dir / "run_gltf").string());
  ASSERT_EQ(gltf_run.exit_code, 0) << gltf_run.output;
  const std::string gltf = (m_dir / "run_gltf" / "mesh_0001.gltf").string();
  const CommandResult gltf_z = run_weft("turntable " + gltf + " --up z --out " + (m_dir / "bad2").string(),
                                        path_env(-1));
  EXPECT_EQ(gltf_z.exit_code, 1) << gltf_z.output;
  EXPECT_CONTAINS(gltf_z.output, "y-up by definition");
  const CommandResult bad_axis = run_weft("turntable " + gltf + " --up x --out " + (m_dir / "bad3").string(),
                                          path_env(-1));
  EXPECT_EQ(bad_axis.exit_code, 1) << bad_axis.output;
  EXPECT_CONTAINS(bad_axis.output, "--up: expected y or z, got 'x'");
  for (const char* bad : {"bad1", "bad2", "bad3"}) EXPECT_FALSE(fs::exists(m_dir / bad)) << bad;
}

}  // namespace
