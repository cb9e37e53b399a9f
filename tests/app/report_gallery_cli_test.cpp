// End to end through the real `weft run --report` and `weft gallery`: the
// report's images and links exist beside it and its plots carry one point per row of stats.csv,
// peaking where stats.csv peaks; the gallery renders each scene of a folder, its final frame is
// the frame `weft run` writes, and a bad scene is listed as failed while the others render.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "render/canvas.h"
#include "render/image.h"
#include "tests/app/cli_test_support.h"

namespace fs = std::filesystem;

namespace {

using weft::app::test::CommandResult;
using weft::app::test::run_weft;
using weft::render::Image;
using weft::render::read_image;

#define EXPECT_CONTAINS(text, part) \
  EXPECT_NE((text).find(part), std::string::npos) << "missing: " << (part) << "\nin: " << (text)

class ReportGalleryCli : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    m_dir = fs::path(WEFT_BINARY_DIR) / "test_output" / "report_gallery_cli" / info->name();
    fs::remove_all(m_dir);
    fs::create_directories(m_dir);
  }
  fs::path write_file(const fs::path& path, const std::string& text) const {
    fs::create_directories((m_dir / path).parent_path());
    std::ofstream(m_dir / path) << text;
    return m_dir / path;
  }
  fs::path m_dir;
};

// A 9×9 cloth pinned at two corners, falling from rest; images of 64×48 pixels.
std::string tiny_scene(int frames) {
  return R"({
  "description": "tiny report test scene <falls & swings>",
  "cloth": {"size": ["20 cm", "20 cm"], "resolution": [9, 9], "origin": [-0.1, 0, 0.5],
            "pins": [{"corner": "u0v1"}, {"corner": "u1v1"}]},
  "output": {"fps": 24, "frames": )" +
         std::to_string(frames) + R"(},
  "render": {"size": [64, 48], "camera": {"eye": [0.6, -0.5, 0.6], "target": [0, 0.1, 0.4]}}
})";
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Column `name` of a CSV file with a header row.
std::vector<double> csv_column(const fs::path& path, const std::string& name) {
  std::ifstream in(path);
  std::string line, cell;
  std::getline(in, line);
  std::stringstream header(line);
  int index = -1;
  for (int k = 0; std::getline(header, cell, ','); ++k)
    if (cell == name) index = k;
  std::vector<double> values;
  if (index < 0) return values;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    for (int k = 0; std::getline(row, cell, ','); ++k)
      if (k == index) values.push_back(std::stod(cell));
  }
  return values;
}

struct Point {
  double x, y;
};

// The points of <polyline data-series="NAME" ... points="x,y x,y ...">.
std::vector<Point> polyline(const std::string& html, const std::string& series) {
  const std::regex pattern("<polyline data-series=\"" + series + "\"[^>]*points=\"([^\"]*)\"");
  std::smatch m;
  std::vector<Point> points;
  if (!std::regex_search(html, m, pattern)) return points;
  std::stringstream s(m[1].str());
  for (std::string pair; s >> pair;) {
    const auto comma = pair.find(',');
    points.push_back({std::stod(pair.substr(0, comma)), std::stod(pair.substr(comma + 1))});
  }
  return points;
}

TEST_F(ReportGalleryCli, ReportLinksExistAndPlotsFollowStatsCsv) {
  const fs::path scene = write_file("tiny.json", tiny_scene(14));
  const fs::path out = m_dir / "run";
  const CommandResult r = run_weft("run " + scene.string() + " --report --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string html = read_text(out / "report.html");
  ASSERT_FALSE(html.empty());
  EXPECT_CONTAINS(html, "tiny report test scene &lt;falls &amp; swings&gt;");
  EXPECT_CONTAINS(html, "--report --out");  // the command

  // Every link is relative and names a file in the folder; the last frame and the sheet are shown.
  const std::regex link("(?:src|href)=\"([^\"]*)\"");
  std::vector<std::string> targets;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), link); it != std::sregex_iterator(); ++it)
    targets.push_back((*it)[1].str());
  for (const std::string& t : targets) {
    EXPECT_EQ(t.find("://"), std::string::npos) << t;
    EXPECT_NE(t.front(), '/') << t;
    EXPECT_TRUE(fs::exists(out / t)) << t;
  }
  for (const char* shown : {"frame_0014.png", "report_sheet.png", "stats.csv"})
    EXPECT_NE(std::find(targets.begin(), targets.end(), shown), targets.end()) << shown;

  // The sheet: 12 of the 14 frames, 64×48 each, in about-square 3 columns × 4 rows.
  const Image sheet = read_image(out / "report_sheet.png");
  const Image frame = read_image(out / "frame_0014.png");
  const int gap = 8;
  EXPECT_EQ(sheet.width(), gap + 3 * (frame.width() + gap));
  // Each row: a frame, its label (the text's height + 4, render/canvas.h) and a gap.
  const int label_h = weft::render::Canvas::text_height() + 4;
  EXPECT_EQ(sheet.height(), gap + 4 * (frame.height() + label_h + gap));

  // One point per stats.csv row, in time order; the plotted peak is stats.csv's peak.
  for (const auto& [series, column] :
       std::vector<std::pair<std::string, std::string>>{{"max_strain", "max_strain"},
                                                        {"kinetic", "kinetic_energy_J"},
                                                        {"gravitational", "gravity_energy_J"},
                                                        {"simulation", "sim_ms"}}) {
    SCOPED_TRACE(series);
    const std::vector<double> values = csv_column(out / "stats.csv", column);
    const std::vector<Point> points = polyline(html, series);
    ASSERT_EQ(values.size(), 14u);
    ASSERT_EQ(points.size(), values.size());
    for (std::size_t k = 1; k < points.size(); ++k) EXPECT_GT(points[k].x, points[k - 1].x);
    // SVG y grows downwards: the largest value is the highest point.
    const auto peak_value = std::max_element(values.begin(), values.end()) - values.begin();
    const double top = std::min_element(points.begin(), points.end(), [](Point a, Point b) {
                         return a.y < b.y;
                       })->y;
    EXPECT_NEAR(points[static_cast<std::size_t>(peak_value)].y, top, 0.1);  // 0.1 px printing
  }
}

TEST_F(ReportGalleryCli, GalleryRendersGoodScenesAndListsTheBadOne) {
  write_file("scenes/a_hang.json", tiny_scene(3));
  write_file("scenes/b_hang.json", tiny_scene(4));
  write_file("scenes/c_bad.json", R"({"description": "bad", "cloth": {"sise": [1, 1]}})");
  const fs::path out = m_dir / "gallery";
  const CommandResult r =
      run_weft("gallery --scenes " + (m_dir / "scenes").string() + " --out " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_CONTAINS(r.output, "scene 3/3: c_bad");
  EXPECT_CONTAINS(r.output, "2 of 3 scenes rendered");
  EXPECT_CONTAINS(r.output, "1 failed:\n  c_bad (");
  EXPECT_CONTAINS(r.output, "sise");  // the scene error names the key

  const std::string readme = read_text(out / "README.md");
  for (const std::string name : {"a_hang", "b_hang"}) {
    SCOPED_TRACE(name);
    EXPECT_CONTAINS(readme, "## " + name + "\n\ntiny report test scene");
    EXPECT_CONTAINS(readme, "![](" + name + ".png)");
    EXPECT_CONTAINS(readme, "![](" + name + "_sheet.png)");
    EXPECT_TRUE(fs::exists(out / (name + "_sheet.png")));
    EXPECT_FALSE(fs::exists(out / (".frames_" + name)));  // scratch frames removed
  }
  EXPECT_CONTAINS(readme, "## c_bad\n\n**Failed:**");
  EXPECT_FALSE(fs::exists(out / "c_bad.png"));

  // The final frame is the last frame of the command the README gives.
  EXPECT_CONTAINS(readme, "b_hang.json --out out/b_hang\n# b_hang.png is out/b_hang/frame_0004.png");
  const fs::path run_out = m_dir / "run_b";
  ASSERT_EQ(run_weft("run " + (m_dir / "scenes/b_hang.json").string() + " --out " + run_out.string()).exit_code, 0);
  const Image gallery_frame = read_image(out / "b_hang.png");
  const Image run_frame = read_image(run_out / "frame_0004.png");
  ASSERT_EQ(gallery_frame.width(), run_frame.width());
  ASSERT_EQ(gallery_frame.height(), run_frame.height());
  EXPECT_TRUE(std::equal(gallery_frame.data(), gallery_frame.data() + 3 * 64 * 48, run_frame.data()));
}

TEST_F(ReportGalleryCli, FramesScaleAndOnly) {
  write_file("scenes/a_hang.json", tiny_scene(8));
  write_file("scenes/b_hang.json", tiny_scene(8));
  const fs::path out = m_dir / "gallery";
  const CommandResult r = run_weft("gallery --scenes " + (m_dir / "scenes").string() +
                                   " --only b_hang --frames-scale 0.25 --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::exists(out / "b_hang.png"));
  EXPECT_FALSE(fs::exists(out / "a_hang.png"));
  const std::string readme = read_text(out / "README.md");
  EXPECT_CONTAINS(readme, "b_hang.json --frames 2 --out out/b_hang");  // 8 × 0.25
  EXPECT_EQ(readme.find("## a_hang"), std::string::npos);

  const CommandResult unknown =
      run_weft("gallery --scenes " + (m_dir / "scenes").string() + " --only nope --out " + out.string());
  EXPECT_EQ(unknown.exit_code, 1);
  EXPECT_CONTAINS(unknown.output, "--only: no scene 'nope' (known: a_hang, b_hang)");
  const CommandResult scale = run_weft("gallery --scenes " + (m_dir / "scenes").string() +
                                       " --frames-scale 0 --out " + out.string());
  EXPECT_EQ(scale.exit_code, 1);
  EXPECT_CONTAINS(scale.output, "--frames-scale: expected a number in (0, 10]");
}

}  // namespace
