// The pieces of weft run --report: frames spread evenly over a run, 1-2-5 axis ticks, and the
// SVG chart's one point per value.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <regex>
#include <sstream>
#include <stdexcept>

#include "app/run_report.h"
#include "app/svg_chart.h"

namespace {

using weft::app::evenly_spaced_frames;
using weft::app::linear_ticks;

TEST(EvenlySpacedFrames, FirstAndLastIncludedAndGapsDifferByAtMostOne) {
  for (const int frames : {12, 13, 50, 72, 97, 1000}) {
    SCOPED_TRACE(frames);
    const std::vector<int> f = evenly_spaced_frames(frames, 12);
    ASSERT_EQ(f.size(), 12u);
    EXPECT_EQ(f.front(), 1);
    EXPECT_EQ(f.back(), frames);
    int lo = frames, hi = 0;
    for (std::size_t k = 1; k < f.size(); ++k) {
      lo = std::min(lo, f[k] - f[k - 1]);
      hi = std::max(hi, f[k] - f[k - 1]);
    }
    EXPECT_GE(lo, 1);
    EXPECT_LE(hi - lo, 1);
  }
  EXPECT_EQ(evenly_spaced_frames(5, 12), (std::vector<int>{1, 2, 3, 4, 5}));
  EXPECT_EQ(evenly_spaced_frames(5, 1), (std::vector<int>{5}));
}

TEST(LinearTicks, StepsOfOneTwoOrFiveTimesAPowerOfTenInsideTheRange) {
  for (const auto& [lo, hi] : std::vector<std::pair<double, double>>{
           {0.0, 1.0}, {-3.2, 7.9}, {1e-6, 4.4e-5}, {100.0, 100.5}, {-2e4, -1e3}}) {
    const std::vector<double> t = linear_ticks(lo, hi);
    ASSERT_GE(t.size(), 2u) << lo << " " << hi;
    const double step = t[1] - t[0];
    const double mantissa = step / std::pow(10.0, std::floor(std::log10(step) + 1e-9));
    EXPECT_TRUE(std::abs(mantissa - 1) < 1e-6 || std::abs(mantissa - 2) < 1e-6 ||
                std::abs(mantissa - 5) < 1e-6) << step;
    EXPECT_GE(t.front(), lo - 1e-9 * step);
    EXPECT_LE(t.back(), hi + 1e-9 * step);
    EXPECT_LT(t.front() - lo, step);  // no tick missing at either end
    EXPECT_LT(hi - t.back(), step);
    EXPECT_LE(t.size(), 11u);
  }
}

TEST(SvgLineChart, AStraightLineStaysStraightAndLengthsMustMatch) {
  weft::app::LineChart chart{"t", "x", "y", {0.0, 1.0, 2.0, 3.0}, {{"line", "#000", {1.0, 3.0, 5.0, 7.0}}}};
  const std::string svg = weft::app::svg_line_chart(chart);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(svg, m, std::regex("data-series=\"line\"[^>]*points=\"([^\"]*)\"")));
  std::vector<double> xs, ys;
  std::stringstream s(m[1].str());
  for (std::string p; s >> p;) {
    xs.push_back(std::stod(p.substr(0, p.find(','))));
    ys.push_back(std::stod(p.substr(p.find(',') + 1)));
  }
  ASSERT_EQ(xs.size(), 4u);
  for (std::size_t k = 2; k < xs.size(); ++k) {  // equal steps in x and y: collinear
    EXPECT_NEAR(xs[k] - xs[k - 1], xs[1] - xs[0], 0.11);
    EXPECT_NEAR(ys[k] - ys[k - 1], ys[1] - ys[0], 0.11);
  }
  EXPECT_LT(ys[3], ys[0]);  // larger values higher up
  chart.series[0].y.pop_back();
  EXPECT_THROW(weft::app::svg_line_chart(chart), std::invalid_argument);
}

}  // namespace
