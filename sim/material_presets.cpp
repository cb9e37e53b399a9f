#include "sim/material_presets.h"

#include <cmath>
#include <stdexcept>

namespace weft::sim {
namespace {

using textile::gf_cm;
using textile::gf_per_cm;
using textile::gf_per_cm2;

// Arguments in textile units: weight gf/cm²; tensile warp, weft and shear rigidity gf/cm (shear
// per radian: KES's G in gf/(cm·deg) × 180/π); bending warp, weft gf·cm.
Material textile_material(double weight, double stretch_warp, double stretch_weft, double shear,
                          double bend_warp, double bend_weft) {
  Material m;
  m.density_kg_m2 = gf_per_cm2(weight);
  m.stretch_warp_N_m = gf_per_cm(stretch_warp);
  m.stretch_weft_N_m = gf_per_cm(stretch_weft);
  m.shear_N_m = gf_per_cm(shear);
  m.bend_warp_Nm = gf_cm(bend_warp);
  m.bend_weft_Nm = gf_cm(bend_weft);
  return m;
}

}  // namespace

// Wang, H., Ramamoorthi, R. and O'Brien, J. F. (2011), "Data-Driven Elastic Models for Cloth:
// Modeling and Measurement", ACM Transactions on Graphics 30(4), 71:1-71:11 (SIGGRAPH 2011).
// They measured ten fabrics (stretch, shear and bending tests) and fitted a piecewise-linear
// model to each; ARCSim (Narain, Samii and O'Brien 2012) distributes the fitted models as its
// material files materials/<fabric>.json, with each fabric's use and fibre content in
// materials/README. The numbers below are typed from those files (as stored in
// github.com/wxhaooo/lyra, materials/, an ARCSim derivative; one stored version). Their meaning is
// fixed by the ARCSim code that reads them (ARCSim 0.2.1/0.3 src/conf.cpp, src/dde.cpp,
// src/physics.cpp, src/mesh.cpp; read in copies on GitHub, nothing of it is used here):
//
// density: mesh.cpp compute_ms_data: face mass = face area × density, so kg/m².
//
// stretching (6 rows × 4): conf.cpp parse(StretchingSamples) makes row 0 the sample at zero
// strain for every direction and rows 1-5 the samples at a principal stretch of 1 + 1/6 along
// 0°, 22.5°, 45°, 67.5°, 90° from u; dde.cpp evaluate_stretching_sample interpolates between
// them by the largest principal stretch ((λ − 1)·6, clamped to [0, 1)), clamps negatives to 0 and
// doubles the result: k = 2·sample. physics.cpp stretching_force applies, per triangle of rest
// area a, the gradient of a·(½k0 ε00² + k1 ε00 ε11 + ½k2 ε11² + k3 ε01²) in the Green strain
// ε = (FᵀF − I)/2 (its comment says so, and grad_e carries 2·k3·ε01; its stretching_energy, used
// for no force, halves the last term — we follow the force). Small strains: a strain ε along u
// costs ½k0 ε², a tension per width k0 ε: stretch_warp = k0 = 2·row0[0] N/m (weft: 2·row0[2]).
// A shear angle γ has ε01 = γ/2 and costs k3 γ²/4 = ½(k3/2) γ²: shear (per radian) = k3/2 =
// row0[3]. k1 (Poisson coupling, often negative and then clamped to 0) has no weft field. Knits
// are soft here (tens of N/m) and stiffen fast: their 1/6-stretch rows are several times row 0
// (the sweater's c22 some 90×), which a linear Material cannot follow.
//
// bending (3 rows × 5): dde.cpp bending_stiffness picks the row by the direction of the hinge
// edge in material space (row 0 along u, 1 at 45°, 2 along v) and the column by
// curv = θ·l/(A0 + A1), the dihedral angle over the mean height of the two triangles, which for a
// cylinder of curvature κ across the edge is κ: column j is read at curv/2 = 5j m⁻¹ ("samples are
// per 0.05 cm^-1 = 5 m^-1"), κ = 0, 10, 20, 30, 40 m⁻¹. Column 0 is the zero-curvature value,
// weft's linear B (the others differ by up to ×2.5 on some fabrics: not representable here).
// physics.cpp bending_force applies, per interior edge of length l between triangles of rest
// areas A0, A1, the gradient of ke·shape·(θ − θ0)²/4 with shape = l²/(2(A0 + A1)), i.e.
//   E = ½ (ke/4) l²/(A0 + A1) (θ − θ0)²,
// which is exactly weft's hinge ½ k θ² with k = B l²/(A0 + A1) (sim/continuum/hinge_kernel.h) for
// B = ke/4; that hinge gives the continuum ½ B κ² per area for a grid bent along an axis
// (HingeBending.CylinderGivesTheContinuumEnergyPerArea; on an equilateral mesh the same hinge
// gives 9/8 of it). So B = ke/4 N·m, with ke from row 2 (edges along v fold when the cloth
// curves along u) for bend_warp and from row 0 for bend_weft. These give Peirce bending lengths
// of 1.2-2.4 cm, the range of garment fabrics.
//
// Which yarn direction (warp/wale or weft/course) ARCSim's u is, the files do not say: weft's
// warp and weft here are ARCSim's u and v. Wang et al. publish no drape coefficient.
Material material_from_arcsim(const ArcsimFabric& fabric) {
  const double used[] = {fabric.density_kg_m2, fabric.stretching[0], fabric.stretching[2],
                         fabric.stretching[3], fabric.bending[0], fabric.bending[2]};
  for (double v : used)
    if (!(std::isfinite(v) && v > 0.0))
      throw std::invalid_argument(
          "material_from_arcsim: density, stretching c11, c22, c33 and bending along u and v must "
          "be finite and > 0");
  Material m;
  m.density_kg_m2 = fabric.density_kg_m2;
  m.stretch_warp_N_m = 2.0 * fabric.stretching[0];
  m.stretch_weft_N_m = 2.0 * fabric.stretching[2];
  m.shear_N_m = fabric.stretching[3];
  m.bend_warp_Nm = fabric.bending[2] / 4.0;
  m.bend_weft_Nm = fabric.bending[0] / 4.0;
  return m;
}

namespace {

// A Wang et al. fabric: its ARCSim file name, its use and fibre content (materials/README), and
// the values of the file used (ArcsimFabric).
MaterialPreset wang2011(const std::string& name, const std::string& file, const std::string& what,
                        const ArcsimFabric& fabric) {
  return {name, material_from_arcsim(fabric),
          "Wang, Ramamoorthi & O'Brien 2011, 'Data-Driven Elastic Models for Cloth: Modeling and "
          "Measurement', ACM Trans. Graph. 30(4) 71, fabric '" + file + "' (" + what +
              "), as ARCSim's materials/" + file +
              ".json: density; stretch = 2 x strain-0 c11, c22 sample, shear = its c33; bending "
              "= zero-curvature hinge ke / 4, warp from edges along v, weft along u (ARCSim's u/v "
              "as warp/weft; sim/material_presets.cpp); no drape coefficient given",
          "", std::nullopt};
}

std::vector<MaterialPreset> make_presets() {
  return {
      // Exact published values: Kang, T. J. and Yu, W. R. (1995), "Drape simulation of woven
      // fabric by using the finite-element method", Journal of the Textile Institute; as quoted in
      // seed 002 (Zhou & Sze), §4: tensile 1118.2 / 759.5 gf/cm, shear 41.8 gf/cm, bending
      // 0.083 / 0.063 gf·cm, weight 0.019 gf/cm² (the table number in Kang & Yu was not checked).
      // Bending length c = 1.635 cm warp, 1.491 cm weft (tests/sim/cantilever_test.cpp).
      // Drape coefficient: the quoting source gives none (Kang & Yu's own measured drape, if
      // any, was not available here).
      {"wool_kang_yu", textile_material(0.019, 1118.2, 759.5, 41.8, 0.083, 0.063),
       "Kang & Yu 1995, J. Textile Inst., 'Drape simulation of woven fabric by using the "
       "finite-element method', as quoted in seed 002 (Zhou & Sze) section 4 (table number "
       "not checked); no drape coefficient given",
       "", std::nullopt},
      // Wang et al. 2011 as ARCSim's files give them: {density}, {stretching row 0}, {bending
      // column 0 of rows 0, 1, 2}.
      wang2011("wang2011_11oz_black_denim", "11oz-black-denim", "jeans, 99% cotton 1% spandex",
               {0.324, {205.352005, 10.234077, 1013.88629, 53.387184},
                {64.196457e-6, 73.384567e-6, 96.951576e-6}}),
      wang2011("wang2011_camel_ponte_roma", "camel-ponte-roma",
               "jacket, 60% polyester 40% rayon",
               {0.284, {31.146198, -12.802702, 44.028667, 31.896357},
                {36.348366e-6, 33.013252e-6, 37.157593e-6}}),
      wang2011("wang2011_gray_interlock", "gray-interlock", "t-shirt, 60% cotton 40% polyester",
               {0.187, {16.593832, -14.695990, 34.477123, 36.860302},
                {23.191698e-6, 24.749964e-6, 14.267624e-6}}),
      wang2011("wang2011_ivory_rib_knit", "ivory-rib-knit", "underwear, 95% cotton 5% spandex",
               {0.276, {42.871021, -0.234556, 65.166023, 83.175644},
                {46.237591e-6, 30.015930e-6, 32.243889e-6}}),
      wang2011("wang2011_navy_sparkle_sweat", "navy-sparkle-sweat",
               "sweater, 96% polyester 4% spandex",
               {0.224, {12.486332, -19.875324, 3.272434, 17.616289},
                {59.469658e-6, 40.072277e-6, 45.625023e-6}}),
      wang2011("wang2011_pink_ribbon_brown", "pink-ribbon-brown", "blanket, 100% polyester",
               {0.228, {151.503906, 106.028160, 244.830673, 30.250183},
                {117.070122e-6, 87.509773e-6, 59.774277e-6}}),
      wang2011("wang2011_royal_target", "royal-target", "pants, 65% cotton 35% polyester",
               {0.220, {2016.55456, 9.170511, 2034.97644, 104.759674},
                {125.409805e-6, 107.997696e-6, 125.409805e-6}}),
      wang2011("wang2011_tango_red_jet_set", "tango-red-jet-set", "jacket, 100% polyester",
               {0.113, {43.067627, 54.373299, 171.424835, 14.314700},
                {14.293814e-6, 21.951700e-6, 20.345654e-6}}),
      wang2011("wang2011_white_dots_on_blk", "white-dots-on-blk", "tablecloth, 100% polyester",
               {0.128, {2002.08618, 0.345588, 2027.48559, 19.189022},
                {51.713814e-6, 40.659470e-6, 31.282822e-6}}),
      wang2011("wang2011_white_swim_solid", "white-swim-solid", "swimsuit, 87% nylon 13% spandex",
               {0.204, {47.971176, 6.834521, 104.615456, 60.773663},
                {60.237942e-6, 58.803211e-6, 51.018833e-6}}),
  };
}

}  // namespace

double peirce_bending_length_m(double bend_Nm, double density_kg_m2, double gravity_m_s2) {
  if (!(std::isfinite(bend_Nm) && bend_Nm >= 0.0))
    throw std::invalid_argument("peirce_bending_length_m: bending rigidity must be finite and >= 0");
  if (!(std::isfinite(density_kg_m2) && density_kg_m2 > 0.0))
    throw std::invalid_argument("peirce_bending_length_m: areal density must be finite and > 0");
  if (!(std::isfinite(gravity_m_s2) && gravity_m_s2 > 0.0))
    throw std::invalid_argument("peirce_bending_length_m: gravity must be finite and > 0");
  return std::cbrt(bend_Nm / (density_kg_m2 * gravity_m_s2));
}

const std::vector<MaterialPreset>& material_presets() {
  static const std::vector<MaterialPreset> presets = make_presets();
  return presets;
}

std::vector<std::string> material_preset_names() {
  std::vector<std::string> names;
  for (const MaterialPreset& p : material_presets()) names.push_back(p.name);
  return names;
}

const MaterialPreset& material_preset(const std::string& name) {
  for (const MaterialPreset& p : material_presets())
    if (p.name == name) return p;
  std::string known;
  for (const std::string& n : material_preset_names()) known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown material preset '" + name + "' (known: " + known + ")");
}

}  // namespace weft::sim
