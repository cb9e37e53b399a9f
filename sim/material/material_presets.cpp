#include "sim/material/material_presets.h"

#include <cmath>
#include <stdexcept>

#include "sim/material/wang2011_fabrics.h"

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
// materials/README. Their numbers are in sim/material/wang2011_fabrics.cpp. Their meaning is
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
// (the sweater's c22 some 90×), which a linear Material cannot follow: the "_curves" presets
// carry the whole tension–strain curve (wang2011_stretch_law).
//
// bending (3 rows × 5): dde.cpp bending_stiffness picks the row by the direction of the hinge
// edge in material space (row 0 along u, 1 at 45°, 2 along v) and the column by
// curv = θ·l/(A0 + A1), the dihedral angle over the mean height of the two triangles, which for a
// cylinder of curvature κ across the edge is κ: column j is read at curv/2 = 5j m⁻¹ ("samples are
// per 0.05 cm^-1 = 5 m^-1"), κ = 0, 10, 20, 30, 40 m⁻¹. Column 0 is the zero-curvature value,
// the linear presets' B; the others differ by up to ×2.5 on some fabrics, which the "_curves"
// presets carry as a moment–curvature law (wang2011_bending_law).
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

std::string wang2011_source(const Wang2011Fabric& f) {
  return "Wang, Ramamoorthi & O'Brien 2011, 'Data-Driven Elastic Models for Cloth: Modeling and "
         "Measurement', ACM Trans. Graph. 30(4) 71, fabric '" + f.file + "' (" + f.what +
         "), as ARCSim's materials/" + f.file + ".json";
}

// A Wang et al. fabric's zero samples: density, row 0 of stretching, column 0 of bending.
ArcsimFabric zero_samples(const Wang2011Fabric& f) {
  ArcsimFabric a;
  a.density_kg_m2 = f.density_kg_m2;
  for (int c = 0; c < 4; ++c) a.stretching[c] = f.stretching[0][c];
  for (int r = 0; r < 3; ++r) a.bending[r] = f.bending[r][0];
  return a;
}

// The linear preset of a Wang et al. fabric: its zero-strain, zero-curvature samples.
MaterialPreset wang2011_linear(const Wang2011Fabric& f) {
  return {f.preset, material_from_arcsim(zero_samples(f)),
          wang2011_source(f) + ": density; stretch = 2 x strain-0 c11, c22 sample, shear = its "
                               "c33; bending = zero-curvature hinge ke / 4, warp from edges along "
                               "v, weft along u (ARCSim's u/v as warp/weft; "
                               "sim/material/material_presets.cpp); no drape coefficient given",
          "", std::nullopt};
}

// The measured-curves preset "<preset>_curves": the linear one with the tension–strain and
// moment–curvature curves of both directions (sim/material/wang2011_fabrics.h); its stretch and
// bending rigidities become the curves' slopes at zero.
MaterialPreset wang2011_curves(const Wang2011Fabric& f) {
  Material m = material_from_arcsim(zero_samples(f));
  m.stretch_law_warp = wang2011_stretch_law(f, FabricAxis::u);
  m.stretch_law_weft = wang2011_stretch_law(f, FabricAxis::v);
  m.bend_law_warp = wang2011_bending_law(f, FabricAxis::u);
  m.bend_law_weft = wang2011_bending_law(f, FabricAxis::v);
  m.stretch_warp_N_m = m.stretch_law_warp->initial_stiffness();
  m.stretch_weft_N_m = m.stretch_law_weft->initial_stiffness();
  m.bend_warp_Nm = m.bend_law_warp->initial_rigidity();
  m.bend_weft_Nm = m.bend_law_weft->initial_rigidity();
  return {f.preset + "_curves", m,
          wang2011_source(f) + ": density, shear = strain-0 c33; tension against strain along "
                               "u, v from the c11, c22 samples at no stretch and at 7/6 stretch; "
                               "bending moment against curvature to 30 1/m from the hinge ke / 4 "
                               "of edges along v (warp) and u (weft) (ARCSim's u/v as warp/weft; "
                               "sim/material/wang2011_fabrics.h); no drape coefficient given",
          "", std::nullopt};
}

std::vector<MaterialPreset> make_presets() {
  std::vector<MaterialPreset> presets{
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
       "", std::nullopt}};
  // Wang et al. 2011: the linear presets, then the measured curves.
  for (const Wang2011Fabric& f : wang2011_fabrics()) presets.push_back(wang2011_linear(f));
  for (const Wang2011Fabric& f : wang2011_fabrics()) presets.push_back(wang2011_curves(f));
  return presets;
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
