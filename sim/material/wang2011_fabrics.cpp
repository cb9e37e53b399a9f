#include "sim/material/wang2011_fabrics.h"

#include <algorithm>
#include <iterator>
#include <utility>

namespace weft::sim {

// Typed from ARCSim 0.3.1's materials/<fabric>.json (github.com/Wajov/arcsim-0.3.1, commit
// 0961778; identical in 0.2.1, github.com/pernorc85/ARCSim-0.2.1, commit ba616ec), as
// assets/fabrics/arcsim_materials.json records them: {preset, file, use and fibres, density,
// stretching 6 × 4, bending 3 × 5}.
namespace {
const Wang2011Fabric kWang2011Fabrics[] = {
  {"wang2011_11oz_black_denim", "11oz-black-denim", "jeans, 99% cotton 1% spandex", 0.324,
     {{205.352005, 10.234077, 1013.88629, 53.387184},
      {232.027634, 40.646339, 1052.84289, 64.980499},
      {224.592209, 40.384563, 1054.43444, 67.184807},
      {225.95105, 62.095657, 1059.59741, 83.99202},
      {226.039566, 40.502792, 1058.27771, 75.118423},
      {225.767487, 40.917892, 1051.55712, 71.810631}},
     {{6.4196457e-05, 6.0286175e-05, 6.0943428e-05, 6.2433697e-05, 1.9824701e-05},
      {7.3384567e-05, 5.9671982e-05, 6.1080757e-05, 6.8242569e-05, 3.6033474e-05},
      {9.6951576e-05, 0.000107848228, 0.000113060738, 0.00012056974, 7.9781021e-05}}},
  {"wang2011_camel_ponte_roma", "camel-ponte-roma", "jacket, 60% polyester 40% rayon", 0.284,
     {{31.146198, -12.802702, 44.028667, 31.896357},
      {78.707756, 26.754574, 268.680725, 27.743423},
      {67.368431, 77.767944, 182.273407, -14.661531},
      {113.367035, 54.802021, 175.126572, 44.65733},
      {144.29483, 111.404854, 138.42215, -29.861851},
      {143.933365, 49.654823, 191.777588, 39.491055}},
     {{3.6348366e-05, 4.9585537e-05, 4.574408e-05, 4.7413387e-05, 2.0726685e-05},
      {3.3013252e-05, 2.9744385e-05, 3.5103642e-05, 3.4041019e-05, 1.4439938e-05},
      {3.7157593e-05, 3.4107452e-05, 3.3229435e-05, 3.4685535e-05, 1.0439938e-05}}},
  {"wang2011_gray_interlock", "gray-interlock", "t-shirt, 60% cotton 40% polyester", 0.187,
     {{16.593832, -14.69599, 34.477123, 36.860302},
      {46.364765, 53.694656, 261.013855, -29.691301},
      {49.28511, 87.5961, 206.373993, 22.768457},
      {123.98922, 105.18177, 365.966217, 44.217571},
      {139.686325, 73.59256, 413.553162, -174.43853},
      {127.44381, 85.848587, 405.872833, 32.238411}},
     {{2.3191698e-05, 3.2932217e-05, 3.4406498e-05, 3.901442e-05, 2.3382786e-05},
      {2.4749964e-05, 1.8651314e-05, 1.6370552e-05, 2.5095791e-05, 8.860165e-06},
      {1.4267624e-05, 7.052906e-06, 1.4515154e-05, 2.4665127e-05, 1.9383726e-05}}},
  {"wang2011_ivory_rib_knit", "ivory-rib-knit", "underwear, 95% cotton 5% spandex", 0.276,
     {{42.871021, -0.234556, 65.166023, 83.175644},
      {52.422512, 7.219094, 245.337158, -31.129513},
      {29.482058, -5.146112, 127.130753, 13.068157},
      {91.209549, 4.940307, 109.746452, 27.60943},
      {48.973385, -0.967226, 147.696823, -49.282963},
      {105.649139, 0.416488, 254.593491, 3.472504}},
     {{4.6237591e-05, 6.3086697e-05, 8.3192772e-05, 9.7574425e-05, 8.0726685e-05},
      {3.001593e-05, 3.0097424e-05, 3.0172081e-05, 3.06483e-05, 2.4726685e-05},
      {3.2243889e-05, 3.7341282e-05, 3.8817448e-05, 3.9812527e-05, 3.043782e-05}}},
  {"wang2011_navy_sparkle_sweat", "navy-sparkle-sweat", "sweater, 96% polyester 4% spandex", 0.224,
     {{12.486332, -19.875324, 3.272434, 17.616289},
      {32.172089, 56.01276, 283.46637, -2.438436},
      {48.565407, 94.126335, 180.101227, 4.43908},
      {77.093796, 2.958664, 91.25116, 6.1077},
      {126.205986, 84.471718, 305.131531, 38.495132},
      {92.34317, 117.527084, 243.264908, 47.338436}},
     {{5.9469658e-05, 3.7500004e-05, 3.5787308e-05, 3.5737106e-05, 2.1033506e-05},
      {4.0072277e-05, 3.7446949e-05, 3.5206612e-05, 2.4871773e-05, 9.033506e-06},
      {4.5625023e-05, 3.9520981e-05, 3.0734119e-05, 2.3301662e-05, 1.3033506e-05}}},
  {"wang2011_pink_ribbon_brown", "pink-ribbon-brown", "blanket, 100% polyester", 0.228,
     {{151.503906, 106.02816, 244.830673, 30.250183},
      {164.124344, 33.689709, 268.195221, 30.074625},
      {152.584641, 107.251373, 210.614838, -62.760571},
      {209.604172, 175.223465, 220.19812, 129.643188},
      {98.879021, 107.085518, 326.209442, 44.475986},
      {96.805817, 54.626881, 359.792633, 30.340616}},
     {{0.000117070122, 0.000202682922, 0.000298615936, 0.000244588867, 0.00023843782},
      {8.7509773e-05, 3.6396919e-05, 0.000103628098, 9.1630119e-05, 9.7175949e-05},
      {5.9774277e-05, 5.9260632e-05, 6.4199661e-05, 5.5017326e-05, 5.9221714e-05}}},
  {"wang2011_royal_target", "royal-target", "pants, 65% cotton 35% polyester", 0.22,
     {{2016.55456, 9.170511, 2034.97644, 104.759674},
      {2109.51684, 38.604588, 2173.93969, 19.129177},
      {2109.78002, 60.16531, 2155.51367, 27.81789},
      {2110.33349, 30.987429, 2135.0791, 121.482445},
      {2109.16015, 72.393326, 2124.13525, 40.810982},
      {2109.52612, 63.424015, 2152.73852, 39.885654}},
     {{0.000125409805, 0.000167284561, 0.00021541275, 0.00021509079, 0.000223861038},
      {0.000107997696, 0.000120583267, 0.000144141678, 0.000140606689, 0.000153048309},
      {0.000125409805, 0.000167284561, 0.00021541275, 0.00021509079, 0.000227861038}}},
  {"wang2011_tango_red_jet_set", "tango-red-jet-set", "jacket, 100% polyester", 0.113,
     {{43.067627, 54.373299, 171.424835, 14.3147},
      {75.151695, 82.195221, 236.163773, -7.230383},
      {57.548206, 89.637825, 224.553848, 3.932043},
      {107.244377, 124.801788, 364.583557, 41.386868},
      {178.734039, 178.488907, 371.764618, -30.898058},
      {227.028687, -21.865427, 404.867188, 62.636021}},
     {{1.4293814e-05, 8.949391e-06, 3.0011126e-05, 3.608149e-05, 1.8363136e-05},
      {2.19517e-05, 2.2446325e-05, 1.8408735e-05, 1.9598495e-05, 1.2071854e-05},
      {2.0345654e-05, 2.269688e-05, 1.5698071e-05, 1.3466827e-05, 7.556618e-06}}},
  {"wang2011_white_dots_on_blk", "white-dots-on-blk", "tablecloth, 100% polyester", 0.128,
     {{2002.08618, 0.345588, 2027.48559, 19.189022},
      {2107.22753, 36.371597, 2171.73339, 16.904713},
      {2107.29882, 57.936157, 2153.30712, 24.392872},
      {2107.73291, 28.389059, 2132.72607, 101.462021},
      {2106.9375, 70.149529, 2121.87353, 38.054455},
      {2107.30786, 61.21629, 2150.4768, 37.668823}},
     {{5.1713814e-05, 3.6506981e-05, 6.6360748e-05, 5.2729267e-05, 1.5221714e-05},
      {4.065947e-05, 1.0401686e-05, 2.084782e-05, 3.0993469e-05, 1.2726685e-05},
      {3.1282822e-05, 2.2910311e-05, 2.6350384e-05, 3.0637762e-05, 1.6726685e-05}}},
  {"wang2011_white_swim_solid", "white-swim-solid", "swimsuit, 87% nylon 13% spandex", 0.204,
     {{47.971176, 6.834521, 104.615456, 60.773663},
      {40.369045, 23.092957, 169.66629, -24.68189},
      {40.291599, 48.142597, 138.261612, 9.002558},
      {51.393467, -32.966949, 79.881721, 35.973194},
      {51.500938, 1.86891, 63.693932, -37.540417},
      {68.621185, 40.13195, 124.468513, 36.199604}},
     {{6.0237942e-05, 5.6357208e-05, 6.9698593e-05, 5.5305969e-05, 3.4705532e-05},
      {5.8803211e-05, 6.3121964e-05, 6.1379181e-05, 4.7971302e-05, 1.9383726e-05},
      {5.1018833e-05, 5.0741455e-05, 5.0570576e-05, 5.0006001e-05, 2.4556618e-05}}},
};
}  // namespace

const std::vector<Wang2011Fabric>& wang2011_fabrics() {
  static const std::vector<Wang2011Fabric> fabrics(std::begin(kWang2011Fabrics),
                                                   std::end(kWang2011Fabrics));
  return fabrics;
}

// ARCSim (src/dde.cpp evaluate_stretching_sample) reads the stretching samples at the largest
// principal stretch λ of the Green strain G, interpolating between row 0 (λ = 1) and the row of
// the stretch's direction (λ = 7/6) by s = 6 (λ − 1) clamped to [0, 1], clamping the sample at 0
// and doubling it; src/physics.cpp applies the second Piola–Kirchhoff stress S00 = k0 G00 + k1 G11
// per unit rest width. A strip stretched along u with no lateral strain (G11 = 0, the Poisson
// coupling k1 left out as weft's springs have none) has G00 = (λ² − 1)/2 and carries the tension
// per rest width T = λ S00 (first Piola–Kirchhoff). ARCSim tabulates k on a 1/30 Green-strain
// grid before it interpolates; this is the file's own curve, not that grid's smoothing of it.
StretchLaw wang2011_stretch_law(const Wang2011Fabric& fabric, FabricAxis axis) {
  const int column = axis == FabricAxis::u ? 0 : 2;
  const int row = axis == FabricAxis::u ? 1 : 5;
  const double at_rest = fabric.stretching[0][column];
  const double stretched = fabric.stretching[row][column];
  std::vector<double> strains{1e-4, 1e-3};  // near 0 too: the table's slope at 0 is its first
  for (int i = 1; i <= 10; ++i) strains.push_back(i / 60.0);  // segment's mean slope
  for (double e : {0.2, 0.25, 0.3, 0.4, 0.5}) strains.push_back(e);
  std::vector<std::pair<double, double>> points;
  for (double e : strains) {
    const double lambda = 1.0 + e, s = std::min(1.0, 6.0 * e);
    const double k = 2.0 * std::max(0.0, at_rest + s * (stretched - at_rest));
    points.emplace_back(e, lambda * k * 0.5 * (lambda * lambda - 1.0));
  }
  return StretchLaw::table(std::move(points));
}

// ARCSim (src/dde.cpp bending_stiffness, src/physics.cpp bending_force) applies per hinge the
// secant law ½ ke(κ) l²/(A0 + A1) θ²/4, which on a grid bent about a grid axis is ½ (ke/4) κ² per
// area: a moment per width M = (ke(κ)/4) κ, ke linear in κ between the columns.
BendingLaw wang2011_bending_law(const Wang2011Fabric& fabric, FabricAxis axis) {
  const double* ke = fabric.bending[axis == FabricAxis::u ? 2 : 0];
  std::vector<std::pair<double, double>> points;
  for (int i = 0; i <= 12; ++i) {
    const double kappa = i == 0 ? 0.25 : 2.5 * i;  // near 0 too, as for stretch
    const int j = std::min(2, static_cast<int>(kappa / 10.0));
    const double t = (kappa - 10.0 * j) / 10.0;
    points.emplace_back(kappa, 0.25 * (ke[j] + t * (ke[j + 1] - ke[j])) * kappa);
  }
  return BendingLaw::table(std::move(points));
}

}  // namespace weft::sim
