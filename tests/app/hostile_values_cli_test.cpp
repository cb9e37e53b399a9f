// Values and files beyond what weft can compute, through the real `weft`: energies past what a
// double holds (a density of 1.7e308 kg/m^2 wrote gravity_energy_J = inf with exit 0), a remesh
// h_min the cloth cannot hold (1 µm refined for 144 s before failing), Radiance maps that stb
// reads past their end (a truncated one, or a run count of 0, looped for ever), non-finite OBJ
// normals and colours, mesh formats weft does not read, and a scene path typed from another
// folder. Each is exit 1 at read time, naming the file and key, nothing written.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/app/cli_test_support.h"

namespace fs = std::filesystem;

namespace {

using weft::app::test::CommandResult;
using weft::app::test::run_weft;
using weft::app::test::tiny_scene;

class HostileValuesCli : public weft::app::test::CliDirectoryTest {
 protected:
  HostileValuesCli() : CliDirectoryTest("hostile_values_cli") {}
  // `weft run` of the tiny scene with these options into a fresh folder `name`.
  CommandResult run_tiny(const std::string& name, const std::string& options) {
    return run_weft("run " + write_scene("tiny.json", tiny_scene()).string() + " " + options +
                    " --out " + (m_dir / name).string());
  }
};

TEST_F(HostileValuesCli, EnergiesBeyondADoubleAreRefusedNamingTheKey) {
  const CommandResult dense = run_tiny("dense", "--set cloth.material.density=1.7e308");
  EXPECT_EQ(dense.exit_code, 1) << dense.output;
  EXPECT_CONTAINS(dense.output, "tiny.json: cloth.material.density: 1.7e+308 kg/m^2 gives the cloth");
  EXPECT_CONTAINS(dense.output, "expected at most ");
  EXPECT_FALSE(fs::exists(m_dir / "dense")) << "refused before anything is written";
  // Implicit Euler: no automatic step to refuse the stiffness first.
  const CommandResult stiff = run_tiny("stiff", "--set simulation.integrator=implicit_euler "
                                                "--set cloth.material.stretch_weft=1e308");
  EXPECT_EQ(stiff.exit_code, 1) << stiff.output;
  EXPECT_CONTAINS(stiff.output, "tiny.json: cloth.material.stretch_weft: 1e+308 N/m gives an "
                                "elastic energy up to 5e+307 J at simulation.max_strain");
  EXPECT_CONTAINS(stiff.output, "more than 1e+305 J");
  EXPECT_FALSE(fs::exists(m_dir / "stiff"));
  // The largest density the message gives runs, and its stats.csv holds numbers only.
  const std::size_t at = dense.output.find("expected at most ");
  ASSERT_NE(at, std::string::npos);
  const double largest = std::stod(dense.output.substr(at + 17));
  const CommandResult heavy =
      run_tiny("heavy", "--frames 1 --set cloth.material.density=" + std::to_string(largest / 2));
  ASSERT_TRUE(heavy.exit_code == 0 || heavy.exit_code == 3) << heavy.output;
  const std::string stats = weft::app::test::file_bytes(m_dir / "heavy" / "stats.csv");
  ASSERT_FALSE(stats.empty()) << heavy.output;
  EXPECT_EQ(stats.find("inf"), std::string::npos) << stats;
  EXPECT_EQ(stats.find("nan"), std::string::npos) << stats;
}

TEST_F(HostileValuesCli, ARemeshHMinTheClothCannotHoldIsRefusedAtReadTime) {
  const fs::path scene = fs::path(WEFT_SOURCE_DIR) / "assets/scenes/disc_drape_50_remeshed.json";
  const CommandResult r = run_weft("run " + scene.string() + " --set simulation.remesh.h_min=1e-6"
                                   " --out " + (m_dir / "fine").string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_CONTAINS(r.output, "disc_drape_50_remeshed.json: simulation.remesh.h_min: 1e-06 m would "
                            "make the cloth (0.25 m^2) a mesh of about 2.89e+11 vertices");
  EXPECT_CONTAINS(r.output, "more than simulation.remesh.max_vertices (200000)");
  EXPECT_FALSE(fs::exists(m_dir / "fine"));
}

// A Radiance file of 8 × 4 texels, run-length encoded: each scanline 2, 2, 0, 8 then one run of
// 8 per channel.
std::string radiance_header() {
  return "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 8\n";
}
std::string radiance_scanline() {
  return std::string("\x02\x02\x00\x08\x88\x80\x88\x80\x88\x80\x88\x81", 12);
}

TEST_F(HostileValuesCli, TruncatedOrCorruptRadianceMapsAreRefused) {
  const std::string line = radiance_scanline();
  const std::vector<std::pair<std::string, std::string>> maps = {
      {"whole", radiance_header() + line + line + line + line},
      {"truncated", radiance_header() + line + line + line.substr(0, 5)},
      {"zero_run", radiance_header() + line + std::string("\x02\x02\x00\x08\x00", 5) + line}};
  for (const auto& [name, bytes] : maps) {
    std::ofstream(m_dir / (name + ".hdr"), std::ios::binary) << bytes;
    const fs::path scene = write_scene(name + ".json", R"({"description": "an environment map",
  "cloth": {"size": ["20 cm", "20 cm"], "resolution": [5, 5]}, "output": {"frames": 1},
  "render": {"size": [32, 24], "environment": {"file": ")" + name + R"(.hdr"}}})");
    const CommandResult r = run_weft("run " + scene.string() + " --out " + (m_dir / name).string());
    if (name == "whole") {
      EXPECT_EQ(r.exit_code, 0) << r.output;
      continue;
    }
    EXPECT_EQ(r.exit_code, 1) << name << "\n" << r.output;
    EXPECT_CONTAINS(r.output, name + ".json: render.environment.file");
    EXPECT_CONTAINS(r.output, name == "truncated" ? "the pixel data ends in scanline 3 of 4"
                                                  : "a run-length count of 0 in scanline 2");
    EXPECT_FALSE(fs::exists(m_dir / name));
  }
}

TEST_F(HostileValuesCli, NonFiniteObjNormalsAndColoursAndOtherFormatsAreRefused) {
  const std::string faces = "v 0 0 0\nv 0.2 0 0\nv 0 0.2 0\n";
  const std::vector<std::pair<std::string, std::string>> files = {
      {"normal.obj", faces + "vn 0 0 nan\nf 1//1 2//1 3//1\n"},
      {"colour.obj", "v 0 0 0 1 1e39 0\nv 0.2 0 0 1 0 0\nv 0 0.2 0 1 0 0\nf 1 2 3\n"},
      {"cube.dae", "<?xml version=\"1.0\"?><COLLADA></COLLADA>\n"},
      // Positions of type VEC2 crashed assimp (SIGSEGV) as a GLB; refused from the JSON.
      {"flat.gltf", R"({"asset":{"version":"2.0"},"accessors":[{"componentType":5126,"count":3,)"
                    R"("type":"VEC2"}],"meshes":[{"primitives":[{"mode":4,"attributes":)"
                    R"({"POSITION":0}}]}]})"}};
  for (const auto& [name, text] : files) {
    std::ofstream(m_dir / name) << text;
    const fs::path scene = write_scene(
        name + ".json", tiny_scene("", ",\n  \"obstacles\": [{\"mesh\": {\"file\": \"" + name + "\"}}]"));
    const CommandResult r = run_weft("run " + scene.string() + " --out " + (m_dir / "o").string());
    EXPECT_EQ(r.exit_code, 1) << name << "\n" << r.output;
    EXPECT_CONTAINS(r.output, (m_dir / name).string() + ": ");
    const std::string why = name == "normal.obj"
                                ? "line 4: normal 'vn 0 0 nan': 'nan' is not a finite number"
                            : name == "colour.obj" ? "line 1: vertex colour 'v 0 0 0 1 1e39 0'"
                            : name == "flat.gltf"  ? "POSITION is accessor 0 of type VEC2"
                                                   : "expected an OBJ, PLY, STL, glTF or FBX file";
    EXPECT_CONTAINS(r.output, why);
    EXPECT_FALSE(fs::exists(m_dir / "o"));
  }
}

TEST_F(HostileValuesCli, ASceneTypedFromAnotherFolderNamesWeftsOwnByItsBareName) {
  const CommandResult r = run_weft("run " + (m_dir / "assets/scenes/sphere_drape.json").string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_CONTAINS(r.output, "cannot read scene file");
  EXPECT_CONTAINS(r.output, "give its bare name, sphere_drape (as in weft run sphere_drape)");
}

}  // namespace
