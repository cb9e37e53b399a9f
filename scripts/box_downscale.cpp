// Box-filter downscaling of a photo for tests/data and gallery/: crops the image to
// a multiple of the factor (dropping the last columns and rows) and averages each factor ×
// factor block, so pixel (c, r) of the result covers pixels factor·c … factor·c + factor − 1
// of the original and a scale of s mm/px becomes factor·s. Reads PNG/JPG, writes PNG (stb).
//
//   g++ -O2 -o /tmp/box_downscale scripts/box_downscale.cpp
//   /tmp/box_downscale ../shared/photos/bendstiff/example_image.jpg \
//       tests/data/photos/bendstiff/example_image_x4.png 4
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <cstdio>
#include <cstdlib>
#include <vector>

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: box_downscale IN OUT.png FACTOR\n");
    return 1;
  }
  int w = 0, h = 0, channels = 0;
  unsigned char* in = stbi_load(argv[1], &w, &h, &channels, 3);
  if (!in) {
    std::fprintf(stderr, "%s: %s\n", argv[1], stbi_failure_reason());
    return 1;
  }
  const int f = std::atoi(argv[3]);
  if (f < 1 || f > w || f > h) {
    std::fprintf(stderr, "FACTOR must be in 1 … min(width, height)\n");
    return 1;
  }
  const int W = w / f, H = h / f;
  std::vector<unsigned char> out(static_cast<std::size_t>(W) * H * 3);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      for (int c = 0; c < 3; ++c) {
        int sum = 0;
        for (int j = 0; j < f; ++j)
          for (int i = 0; i < f; ++i) sum += in[((y * f + j) * w + x * f + i) * 3 + c];
        out[(static_cast<std::size_t>(y) * W + x) * 3 + c] =
            static_cast<unsigned char>((sum + f * f / 2) / (f * f));
      }
  stbi_image_free(in);
  if (!stbi_write_png(argv[2], W, H, 3, out.data(), W * 3)) {
    std::fprintf(stderr, "%s: cannot write\n", argv[2]);
    return 1;
  }
  std::printf("%s: %d×%d → %d×%d\n", argv[2], w, h, W, H);
  return 0;
}
