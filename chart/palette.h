#pragma once
// The colours of weft's charts, chosen to stay apart for colour-blind readers.
//
// Lines and markers: the eight colours of Okabe & Ito, "Color Universal Design" (2008), which
// stay distinct under protanopia, deuteranopia and tritanopia. Heatmaps: viridis (van der Walt
// & Smith, matplotlib 1.5), perceptually uniform and readable in grey, as five stops
// interpolated linearly in sRGB.

#include <array>
#include <cstddef>
#include <string>

#include "render/image.h"

namespace weft::chart {

using render::Rgb8;

namespace okabe_ito {
constexpr Rgb8 black{0, 0, 0};
constexpr Rgb8 orange{230, 159, 0};
constexpr Rgb8 sky_blue{86, 180, 233};
constexpr Rgb8 bluish_green{0, 158, 115};
constexpr Rgb8 yellow{240, 228, 66};
constexpr Rgb8 blue{0, 114, 178};
constexpr Rgb8 vermillion{213, 94, 0};
constexpr Rgb8 reddish_purple{204, 121, 167};
// In Okabe and Ito's order.
constexpr std::array<Rgb8, 8> all{black, orange, sky_blue, bluish_green,
                                  yellow, blue, vermillion, reddish_purple};
}  // namespace okabe_ito

// The k-th colour for a data series: vermillion, blue, bluish green, reddish purple, orange,
// sky blue, then again (black and yellow are left for text and for light backgrounds).
Rgb8 series_colour(std::size_t k);

// viridis at t ∈ [0, 1] (clamped): #440154 at 0, #3b528b, #21918c, #5ec962, #fde725 at 1.
Rgb8 viridis(double t);
constexpr std::array<Rgb8, 5> kViridisStops{{{68, 1, 84}, {59, 82, 139}, {33, 145, 140},
                                             {94, 201, 98}, {253, 231, 37}}};

// Ink and greys of the frame and text.
constexpr Rgb8 kInk{20, 20, 20}, kGrey{110, 110, 110}, kLightGrey{160, 160, 160};
constexpr Rgb8 kGrid{228, 228, 228}, kWhite{255, 255, 255};

// "#rrggbb".
std::string hex(Rgb8 colour);

}  // namespace weft::chart
