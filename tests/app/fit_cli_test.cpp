// End to end through the real `weft fit`: a measured-number fit of the bendstiff strip writes
// its log, plots, fitted scene and report, and the fitted scene runs; bad fit files are errors
// naming the file and key, with nothing written; a drape photos fit reports every image.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include "app/io/npy_file.h"
#include "tests/app/cli_test_support.h"

namespace fs = std::filesystem;

namespace {

using weft::app::test::CommandResult;
using weft::app::test::run_weft;

const std::string kStrip = std::string(WEFT_SOURCE_DIR) + "/assets/scenes/bendstiff_strip.json";

class FitCli : public weft::app::test::CliDirectoryTest {
 protected:
  FitCli() : CliDirectoryTest("fit_cli") {}
  // A fit file of the strip with these parameters and target.
  fs::path write_fit(const std::string& parameters, const std::string& target,
                     const std::string& scene = kStrip) const {
    return write_scene("fit.json", R"({"description": "test", "scene": ")" + scene +
                                       R"(", "parameters": )" + parameters + R"(, "target": )" +
                                       target + R"(, "profile": {"points": 1}})");
  }
};

TEST_F(FitCli, MeasuredFitWritesEverythingAndTheFittedSceneRuns) {
  const fs::path fit = write_fit(R"([{"name": "bend", "start": "0.05 N*m"}])",
                                 R"({"measured": {"drop": "80 mm"}})");
  const CommandResult r = run_weft("fit " + fit.string() + " --out " + (m_dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_CONTAINS(r.output, "fit eval   1  bend=0.05 N*m  objective");
  EXPECT_CONTAINS(r.output, "bend band");
  for (const char* file : {"fit.csv", "fit_result.json", "fitted_scene.json", "fit.txt",
                           "convergence.png", "profile.png", "report.html"})
    EXPECT_TRUE(fs::exists(m_dir / "out" / file)) << file;
  std::ifstream csv(m_dir / "out" / "fit.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header, "evaluation,phase,bend,objective,settled,iterations,residual,seconds,measures");
  // The fitted scene is a scene: weft measure settles it again.
  const CommandResult m = run_weft("measure " + (m_dir / "out" / "fitted_scene.json").string() +
                                   " --frames 2 --out " + (m_dir / "measure").string());
  EXPECT_EQ(m.exit_code, 0) << m.output;
}

TEST_F(FitCli, BadFitFilesNameTheFileAndKey) {
  const auto expect_error = [&](const fs::path& fit, const std::string& message) {
    const CommandResult r = run_weft("fit " + fit.string() + " --out " + (m_dir / "out").string());
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_CONTAINS(r.output, fit.string());
    EXPECT_CONTAINS(r.output, message);
    EXPECT_FALSE(fs::exists(m_dir / "out"));
  };
  const std::string drop = R"({"measured": {"drop": "80 mm"}})";
  expect_error(write_fit(R"([{"name": "stiffness", "start": 1}])", drop),
               "parameters[0].name: expected one of 'bend', 'bend_warp'");
  expect_error(write_fit(R"([{"name": "bend", "start": "0.05 N/m"}])", drop), "parameters[0].start");
  expect_error(write_fit(R"([{"name": "bend", "start": "0.05 N*m", "min": "0.1 N*m"}])", drop),
               "min ≤ start ≤ max");
  expect_error(write_fit(R"([{"name": "bend", "start": "0.05 N*m"}, {"name": "bend_warp", "start": "0.05 N*m"}])", drop),
               "which parameters[0] sets too");
  expect_error(write_fit(R"([{"name": "bend", "start": "0.05 N*m"}])", R"({"measured": {}})"),
               "target.measured: expected at least one of");
  expect_error(write_fit(R"([{"name": "bend", "start": "0.05 N*m"}])",
                         R"({"point_cloud": {"file": "missing.npy"}})"),
               "target.point_cloud.file:");
  expect_error(write_fit(R"([{"name": "bend", "start": "0.05 N*m"}])",
                         R"({"photo": {"image": ")" + std::string(WEFT_SOURCE_DIR) +
                             R"(/tests/data/photos/bendstiff/example_image_x4.png"}})"),
               "is 548×323 px but the scene renders 2193×1294");
  expect_error(write_fit(R"([{"name": "bend", "start": "0.05 N*m"}])", drop, "nowhere.json"),
               "nowhere.json: cannot read scene file");
}

// --threads on weft fit reaches every evaluation's scene (here self-collision's
// candidate search, which runs on the threads) and changes no bit of the fit: the log (but for
// its wall-clock seconds) and the fitted scene are the same for 1 and 3 threads. A bad count is
// refused naming the option, with nothing written.
TEST_F(FitCli, ThreadsChangeNoBitOfTheFit) {
  const fs::path fit = write_scene(
      "fit.json", R"({"description": "test", "scene": ")" + kStrip + R"(",
        "set": {"simulation.self_collision": {}},
        "parameters": [{"name": "bend", "start": "0.05 N*m"}],
        "target": {"measured": {"drop": "80 mm"}}, "profile": {"points": 0}})");
  // fit.csv without its seconds column (the 8th).
  const auto log_without_seconds = [](const fs::path& csv) {
    std::ifstream in(csv);
    std::string out;
    for (std::string line; std::getline(in, line);) {
      std::stringstream fields(line);
      std::string field;
      for (int column = 1; std::getline(fields, field, ','); ++column)
        if (column != 8) out += field + ",";
      out += "\n";
    }
    return out;
  };
  const auto file_text = [](const fs::path& path) {
    std::ifstream in(path);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  for (const char* threads : {"1", "3"}) {
    const CommandResult r = run_weft("fit " + fit.string() + " --max-evaluations 3 --threads " +
                                     threads + " --out " + (m_dir / threads).string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  const std::string one = log_without_seconds(m_dir / "1" / "fit.csv");
  EXPECT_GT(std::count(one.begin(), one.end(), '\n'), 3) << one;  // a header and 3 evaluations
  EXPECT_EQ(one, log_without_seconds(m_dir / "3" / "fit.csv"));
  EXPECT_EQ(file_text(m_dir / "1" / "fitted_scene.json"), file_text(m_dir / "3" / "fitted_scene.json"));

  const CommandResult bad =
      run_weft("fit " + fit.string() + " --threads -1 --out " + (m_dir / "bad").string());
  EXPECT_EQ(bad.exit_code, 1) << bad.output;
  EXPECT_CONTAINS(bad.output, "--threads");
  EXPECT_FALSE(fs::exists(m_dir / "bad"));
}

// A drape photos fit through the command, two evaluations (static solves): its progress lines
// carry the objective's parts, its last lines compare the fitted drape with every image (the
// held-out ones marked), and it writes the drape pictures; a mistake names its key.
TEST_F(FitCli, DrapePhotosFitComparesEveryImageAndWritesItsPictures) {
  const std::string data = std::string(WEFT_SOURCE_DIR) + "/tests/data/photos/cusick_synthetic/";
  const auto fit_with = [&](const std::string& images) {
    return write_scene("fit.json", R"({"scene": ")" + std::string(WEFT_SOURCE_DIR) +
                                       R"(/assets/scenes/cusick_drape.json",
        "set": {"cloth.resolution": [25, 25], "cloth.pins": [{"grid": [12, 12]}]},
        "parameters": [{"name": "bend", "start": "1.2e-5 N*m"}],
        "target": {"drape_photos": {)" + images + R"(, "mm_per_px": 0.5, "specimen": "30 cm", "support": "18 cm"}},
        "profile": {"points": 0}})");
  };
  const fs::path fit = fit_with(R"("images": [")" + data + R"(drape_0deg.png"], "check_images": [")" + data +
                                R"(check_27x27.png"])");
  const CommandResult r = run_weft("fit " + fit.string() + " --max-evaluations 2 --out " + (m_dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* part : {"outline_part", "dc_part", "nodes_part"}) EXPECT_CONTAINS(r.output, part);
  EXPECT_CONTAINS(r.output, "  drape_0deg.png: DC 0.558 (fitted ");
  EXPECT_CONTAINS(r.output, "  held out check_27x27.png: DC 0.570 (fitted ");
  for (const char* file : {"drape_photos.png", "outline_spectra.png", "report.html", "fit_result.json"})
    EXPECT_TRUE(fs::exists(m_dir / "out" / file)) << file;

  const CommandResult bad = run_weft("fit " + fit_with(R"("images": [")" + data + R"(nowhere.png"])").string() +
                                     " --out " + (m_dir / "bad").string());
  EXPECT_EQ(bad.exit_code, 1) << bad.output;
  EXPECT_CONTAINS(bad.output, "fit.json: target.drape_photos.images[0]: image ");
  EXPECT_CONTAINS(bad.output, "nowhere.png: no such file");
  EXPECT_FALSE(fs::exists(m_dir / "bad"));
}

// A point cloud at 1e300 m: every objective is infinite. This used to exit 0, reporting the
// start as the fit.
TEST_F(FitCli, AFitWithNoFiniteObjectiveFails) {
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> far(2, 3);
  far << 1e300, 0, 0, 0, 1e300, 0;
  weft::app::write_npy_points(m_dir / "far.npy", far);
  const fs::path fit = write_fit(R"([{"name": "bend", "start": "0.05 N*m"}])",
                                 R"({"point_cloud": {"file": "far.npy"}})");
  const CommandResult r = run_weft("fit " + fit.string() + " --max-evaluations 2 --out " +
                                   (m_dir / "out").string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_CONTAINS(r.output, fit.string() + ": target: none of the ");
  EXPECT_CONTAINS(r.output, "evaluations gave a finite objective");
}

}  // namespace
