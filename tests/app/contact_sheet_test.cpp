// Contact sheets (app/report/contact_sheet.h): the box-filtered thumbnail keeps the mean colour, and
// the sheet lays the thumbnails out in the grid its size says, each framed and labelled.
#include "app/report/contact_sheet.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "render/canvas.h"

namespace {

using weft::app::contact_sheet;
using weft::app::contact_sheet_columns;
using weft::app::thumbnail;
using weft::render::Image;
using weft::render::Rgb8;

double mean_red(const Image& image) {
  double sum = 0.0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) sum += image.at(x, y).r;
  return sum / (image.width() * image.height());
}

TEST(Thumbnail, HalvingStripesAveragesEachPair) {
  Image stripes(64, 32);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x) stripes.set(x, y, x % 2 ? Rgb8{200, 0, 0} : Rgb8{100, 0, 0});
  const Image t = thumbnail(stripes, 32);
  ASSERT_EQ(t.width(), 32);
  ASSERT_EQ(t.height(), 16);
  for (int y = 0; y < t.height(); ++y)
    for (int x = 0; x < t.width(); ++x) EXPECT_EQ(t.at(x, y).r, 150);
}

TEST(Thumbnail, ANonIntegerFactorKeepsTheMeanAndTheAspect) {
  Image ramp(640, 480);
  for (int y = 0; y < 480; ++y)
    for (int x = 0; x < 640; ++x)
      ramp.set(x, y, {static_cast<std::uint8_t>((x * 7 + y * 3) % 256), 0, 0});
  const Image t = thumbnail(ramp, 192);
  EXPECT_EQ(t.width(), 192);
  EXPECT_EQ(t.height(), 144);
  EXPECT_NEAR(mean_red(t), mean_red(ramp), 0.5);  // rounding only
  EXPECT_EQ(thumbnail(ramp, 800).width(), 640);   // never enlarged
  EXPECT_THROW(thumbnail(ramp, 0), std::invalid_argument);
}

TEST(ContactSheet, ColumnsMakeANearlySquareSheet) {
  EXPECT_EQ(contact_sheet_columns(1, 640, 480), 1);
  EXPECT_EQ(contact_sheet_columns(4, 640, 480), 2);
  EXPECT_EQ(contact_sheet_columns(12, 640, 480), 3);
  EXPECT_EQ(contact_sheet_columns(36, 640, 480), 6);
  EXPECT_EQ(contact_sheet_columns(3, 100, 1000), 3);  // tall tiles: one row
}

TEST(ContactSheet, GridOfThumbnailsWithLabels) {
  const int w = 40, h = 30, gap = 8;
  std::vector<Image> tiles;
  std::vector<std::string> labels;
  for (int k = 0; k < 5; ++k) {
    tiles.emplace_back(w, h, Rgb8{static_cast<std::uint8_t>(40 * k), 90, 200});
    labels.push_back(std::to_string(72 * k) + " deg");
  }
  const Image sheet = contact_sheet(tiles, labels, 3, gap);
  const int label_h = weft::render::Canvas::text_height() + 4;
  EXPECT_EQ(sheet.width(), gap + 3 * (w + gap));
  EXPECT_EQ(sheet.height(), gap + 2 * (h + label_h + gap));
  for (int k = 0; k < 5; ++k) {  // each tile's centre shows its own colour
    const int x = gap + (k % 3) * (w + gap) + w / 2, y = gap + (k / 3) * (h + label_h + gap) + h / 2;
    EXPECT_EQ(sheet.at(x, y), tiles[static_cast<std::size_t>(k)].at(0, 0)) << k;
  }
  // Ink under the first tile (its label), none in the empty sixth cell.
  int ink = 0, empty_ink = 0;
  for (int y = gap + h + 1; y < gap + h + label_h; ++y) {
    for (int x = gap; x < gap + w; ++x) ink += sheet.at(x, y).r < 128;
    for (int x = gap + 2 * (w + gap); x < gap + 2 * (w + gap) + w; ++x)
      empty_ink += sheet.at(x, y + h + label_h + gap).r < 128;
  }
  EXPECT_GT(ink, 10);
  EXPECT_EQ(empty_ink, 0);
  EXPECT_THROW(contact_sheet({}, {}, 3), std::invalid_argument);
  EXPECT_THROW(contact_sheet(tiles, {"one"}, 3), std::invalid_argument);
}

}  // namespace
