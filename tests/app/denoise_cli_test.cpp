// `weft run --renderer raytrace` denoises by default and `--denoise off` does not; the
// denoised frame is the same bytes for 1 and 2 threads.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <string>
#include <utility>

#include "render/image.h"
#include "tests/app/cli_test_support.h"

namespace weft::app {
namespace {

class DenoiseCli : public test::CliDirectoryTest {
 protected:
  DenoiseCli() : CliDirectoryTest("denoise_cli") {}
};

// Sum over pixels of |I(x+1, y) − I(x, y)| in the green channel: pixel-to-pixel noise shows up
// here; denoising lowers it.
long roughness(const render::Image& image) {
  long sum = 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x + 1 < image.width(); ++x) sum += std::abs(image.at(x + 1, y).g - image.at(x, y).g);
  return sum;
}

TEST_F(DenoiseCli, OnByDefaultOffOnRequestSameBytesForAnyThreads) {
  const auto scene = write_scene("tiny.json", test::tiny_scene());
  const std::string common =
      "run " + scene.string() + " --frames 1 --size 160x120 --renderer raytrace --samples 4 ";
  const std::pair<std::string, std::string> runs[] = {
      {"on1", "--threads 1"}, {"on2", "--threads 2"}, {"off", "--denoise off --threads 2"}};
  for (const auto& [name, args] : runs) {
    const auto r = test::run_weft(common + args + " --out " + (m_dir / name).string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  const auto frame = [&](const std::string& name) {
    return render::read_image(m_dir / name / "frame_0001.png");
  };
  const render::Image on1 = frame("on1"), on2 = frame("on2"), off = frame("off");
  EXPECT_TRUE(std::equal(on1.data(), on1.data() + 3 * 160 * 120, on2.data()));
  EXPECT_FALSE(std::equal(on1.data(), on1.data() + 3 * 160 * 120, off.data()));
  std::printf("roughness: denoised %ld, plain %ld\n", roughness(on1), roughness(off));
  EXPECT_LT(roughness(on1), roughness(off));
}

}  // namespace
}  // namespace weft::app
