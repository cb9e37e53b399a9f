// Disc-shaped specimens (SpecimenShape::disc, the Cusick drape test's Ø30 cm circle): the kept
// area against π r², masses, uniform-strain energies, free fall under every model, unused
// vertices, pins; and the rectangle, which keeps every cell.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "base/constants.h"
#include "sim/cloth_model.h"
#include "sim/grid.h"
#include "sim/mass_spring.h"
#include "sim/material/material_presets.h"
#include "sim/pins.h"
#include "sim/simulator.h"

namespace weft::sim {
namespace {
constexpr double kDiameter_m = 0.30;  // Cusick specimen, BS 5058 / ISO 9073-9

ClothMesh disc(Index n, double diameter_m = kDiameter_m, double elongation = 1.0) {
  GridSpec spec;
  spec.size_u_m = diameter_m * elongation;
  spec.size_v_m = diameter_m;
  spec.nu = spec.nv = n;
  spec.origin = Vec3(-0.5 * spec.size_u_m, -0.5 * spec.size_v_m, 0.3);
  spec.shape = SpecimenShape::disc;
  return make_grid(spec);
}

double cell_area_m2(const ClothMesh& mesh) {
  const Vec2 d = mesh.material_coords[static_cast<std::size_t>(mesh.index(1, 1))] -
                 mesh.material_coords[static_cast<std::size_t>(mesh.index(0, 0))];
  return d.x() * d.y();
}

const Material& wool() { return material_preset("wool_kang_yu").material; }

// The kept cells are those whose centre is in the disc. Every cell the circle crosses lies in
// the band r ∈ [R − d, R + d], d = h/√2 half a cell diagonal, so |A − πR²| is at most that
// band's area 4πRd = 2√2 π R h: first order, guaranteed. Measured, the error falls about as
// (h/R)^1.5 πR² (irregularly: counting cell centres in a circle is Gauss's circle problem,
// whose error is O(N^θ) in the N cells across, θ between 1/2 and 131/208), 0.6 % at 41², 0.05 %
// at 81², 0.009 % at 161².
TEST(DiscCloth, KeptAreaConvergesToPiRSquared) {
  const double r = 0.5 * kDiameter_m, exact = base::kPi * r * r;
  double coarse_error = 0.0, fine_error = 0.0;
  for (Index n : {11, 21, 41, 81, 161}) {
    const ClothMesh mesh = disc(n);
    const double h = kDiameter_m / static_cast<double>(n - 1);
    const double area = mesh.vertex_area_m2.sum();
    const double error = std::abs(area - exact);
    EXPECT_NEAR(area, static_cast<double>(mesh.quads.size()) * h * h, 1e-12 * exact) << n;
    EXPECT_LE(error, 2.0 * std::sqrt(2.0) * base::kPi * r * h) << n << " vertices across";
    EXPECT_LE(error / exact, std::pow(h / r, 1.5)) << n << " vertices across";
    if (n == 11) coarse_error = error;
    if (n == 161) fine_error = error;
  }
  EXPECT_LT(fine_error, coarse_error / 50.0);
}

// An elliptical specimen (the disc of a non-square size) converges to π a b the same way.
TEST(DiscCloth, AnEllipseKeepsItsArea) {
  const ClothMesh mesh = disc(121, kDiameter_m, 1.5);
  const double exact = base::kPi * 0.75 * kDiameter_m * 0.5 * kDiameter_m;
  EXPECT_NEAR(mesh.vertex_area_m2.sum(), exact, 0.002 * exact);
}

// Lumped masses: areal density × the kept area, all of it, and nothing on unused vertices.
TEST(DiscCloth, MassIsDensityTimesKeptArea) {
  const ClothMesh mesh = disc(31);
  const Simulator sim(mesh, wool(), {}, SimSettings{});
  const double kept_area_m2 = static_cast<double>(mesh.quads.size()) * cell_area_m2(mesh);
  EXPECT_NEAR(sim.masses_kg().sum(), wool().density_kg_m2 * kept_area_m2,
              1e-13 * wool().density_kg_m2 * kept_area_m2);
  Index unused = 0;
  for (Index v = 0; v < mesh.vertex_count(); ++v) {
    if (mesh.is_used(v)) {
      EXPECT_GT(sim.masses_kg()[v], 0.0);
    } else {
      EXPECT_EQ(sim.masses_kg()[v], 0.0) << "vertex " << v;
      ++unused;
    }
  }
  EXPECT_EQ(unused + mesh.used_vertex_count(), mesh.vertex_count());
  // The four corners of the square are cut off: (1 − π/4) of the square, roughly.
  EXPECT_GT(unused, 100);
}

// Every used vertex belongs to a kept quad and every quad corner is used.
TEST(DiscCloth, UsedVerticesAreTheQuadCorners) {
  const ClothMesh mesh = disc(25);
  std::vector<bool> corner(static_cast<std::size_t>(mesh.vertex_count()), false);
  for (const auto& q : mesh.quads)
    for (Index v : q) corner[static_cast<std::size_t>(v)] = true;
  EXPECT_EQ(corner, mesh.vertex_used);
  // Only vertices within the disc (plus half a cell diagonal) are used.
  const double h = kDiameter_m / 24.0, r = 0.5 * kDiameter_m;
  for (Index v = 0; v < mesh.vertex_count(); ++v) {
    const Vec2 from_centre = mesh.material_coords[static_cast<std::size_t>(v)] - Vec2(r, r);
    if (mesh.is_used(v)) {
      EXPECT_LE(from_centre.norm(), r + h * std::sqrt(2.0) / 2 + 1e-12);
    }
    if (from_centre.norm() < r - h * std::sqrt(2.0)) {
      EXPECT_TRUE(mesh.is_used(v)) << v;
    }
  }
}

// A uniform warp stretch ε (x = X + ε u e_warp) stores ½ Y_warp ε² per unit area in every model
// (docs/models.md), so ½ Y_warp ε² A over the kept area A: the tributary widths of the disc's
// springs and the elements of its kept cells add up to the disc and nothing more.
TEST(DiscCloth, UniformStretchEnergyIsThatOfTheKeptArea) {
  const double strain = 1e-4;
  for (const ClothMesh& mesh : {disc(21), disc(20, kDiameter_m, 1.3)}) {
    Matrix3X x = mesh.rest_positions;
    for (Index v = 0; v < mesh.vertex_count(); ++v)
      x(v, 0) += strain * mesh.material_coords[static_cast<std::size_t>(v)].x();
    const double area = mesh.vertex_area_m2.sum();
    const double expected = 0.5 * wool().stretch_warp_N_m * strain * strain * area;
    for (ClothModel model : all_cloth_models) {
      double energy = 0.0;
      if (model == ClothModel::mass_spring) {
        energy = MassSpringModel(mesh, wool()).energy(x);
      } else {
        for (const auto& term : make_force_terms(mesh, wool(), model, true)) energy += term->energy(x);
      }
      EXPECT_NEAR(energy, expected, 1e-3 * expected) << cloth_model_name(model) << ", " << mesh.nu;
    }
  }
}

// Springs and bends only where their edges belong to kept cells: none touches an unused vertex,
// and the disc's free edge has springs of half the interior stiffness.
TEST(DiscCloth, SpringsAndBendsStayOnTheSpecimen) {
  const ClothMesh mesh = disc(21);
  const MassSpringModel model(mesh, wool());
  ASSERT_FALSE(model.springs().empty());
  ASSERT_FALSE(model.bends().empty());
  double k_min = 1e300, k_max = 0.0;
  for (const Spring& s : model.springs()) {
    EXPECT_TRUE(mesh.is_used(s.a) && mesh.is_used(s.b));
    if (s.kind != SpringKind::warp) continue;
    k_min = std::min(k_min, s.k_N_m);
    k_max = std::max(k_max, s.k_N_m);
  }
  EXPECT_DOUBLE_EQ(k_max, 2.0 * k_min);
  for (const AngularSpring& b : model.bends())
    EXPECT_TRUE(mesh.is_used(b.v0) && mesh.is_used(b.v1) && mesh.is_used(b.v2));
}

void expect_free_fall_keeps_the_disc(const SimSettings& settings, const std::string& what) {
  const ClothMesh mesh = disc(17);
  Simulator sim(mesh, wool(), {}, settings);
  const double t_end_s = 0.05;
  sim.advance(t_end_s);
  // Symplectic Euler from rest under g: x_n = x0 + g h² n(n+1)/2 for every used vertex, all
  // moving together (no strain); unused ones exactly where they started.
  const long n = sim.steps_taken();
  const double h = t_end_s / static_cast<double>(n);
  const Vec3 drop = settings.gravity_m_s2 * h * h * 0.5 * static_cast<double>(n * (n + 1));
  for (Index v = 0; v < mesh.vertex_count(); ++v) {
    const Vec3 x0 = mesh.rest_positions.row(v).transpose();
    const Vec3 x = sim.state().x.row(v).transpose();
    if (mesh.is_used(v)) {
      EXPECT_LT((x - (x0 + drop)).norm(), 1e-9) << what << ": vertex " << v;
    } else {
      EXPECT_EQ(x, x0) << what << ": unused vertex " << v;
      EXPECT_EQ(Vec3(sim.state().v.row(v).transpose()), Vec3::Zero()) << what;
    }
  }
  const Diagnostics d = sim.diagnostics();
  EXPECT_LT(d.max_strain, 1e-9) << what;
  const double speed = settings.gravity_m_s2.norm() * h * static_cast<double>(n);
  EXPECT_NEAR(d.max_speed_m_s, speed, 1e-9) << what;
  EXPECT_NEAR(d.kinetic_energy_J, 0.5 * sim.masses_kg().sum() * speed * speed,
              1e-9 * d.kinetic_energy_J)
      << what;
}

TEST(DiscCloth, FreeFallKeepsTheShapeUnderEveryModel) {
  for (ClothModel model : all_cloth_models) {
    SimSettings settings;
    settings.model = model;
    settings.air_damping_1_s = 0.0;
    expect_free_fall_keeps_the_disc(settings, cloth_model_name(model));
  }
}

TEST(DiscCloth, FreeFallKeepsTheShapeUnderFastProjection) {
  SimSettings settings;
  settings.air_damping_1_s = 0.0;
  settings.projection.method = ProjectionMethod::fast_projection;
  expect_free_fall_keeps_the_disc(settings, "fast projection");
  settings.projection.edges = ConstrainedEdges::triangle_edges;
  expect_free_fall_keeps_the_disc(settings, "fast projection, triangle edges");
}

// Pinned at its centre, the disc droops and its unused vertices stay put, untouched by the
// forces around them.
TEST(DiscCloth, UnusedVerticesNeverMoveWhileTheDiscDroops) {
  const ClothMesh mesh = disc(17);
  const auto pinned = resolve_pins({PinGrid{8, 8}}, mesh);
  Simulator sim(mesh, wool(), pinned, SimSettings{});
  sim.advance(0.1);
  double lowest_used_z = 1e300;
  for (Index v = 0; v < mesh.vertex_count(); ++v) {
    if (mesh.is_used(v))
      lowest_used_z = std::min(lowest_used_z, sim.state().x(v, 2));
    else
      EXPECT_EQ(Vec3(sim.state().x.row(v).transpose()), Vec3(mesh.rest_positions.row(v).transpose()));
  }
  EXPECT_LT(lowest_used_z, mesh.rest_positions(0, 2) - 0.01);  // the rim has fallen
  EXPECT_EQ(sim.pinned(), pinned);  // unused vertices are not reported as pins
}

std::string pin_error(const PinSpec& pin, const ClothMesh& mesh) {
  try {
    (void)resolve_pins({pin}, mesh);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}

TEST(DiscCloth, PinsOnUnusedVerticesAreErrors) {
  const ClothMesh mesh = disc(21);
  EXPECT_EQ(pin_error(PinCorner{"u1v0"}, mesh),
            "pin 0: corner u1v0 is not part of the cloth (outside the trimmed specimen)");
  EXPECT_EQ(pin_error(PinVertex{0}, mesh),
            "pin 0: vertex 0 is not part of the cloth (outside the trimmed specimen)");
  EXPECT_EQ(pin_error(PinGrid{20, 20}, mesh),
            "pin 0: grid vertex [20, 20] is not part of the cloth (outside the trimmed specimen)");
  EXPECT_NE(pin_error(PinRegion{0.0, 0.1, 0.0, 0.1}, mesh).find("contains no vertex of the cloth"),
            std::string::npos);
  // A region across the rim selects the used vertices in it only.
  const auto band = resolve_pins({PinRegion{0.0, 1.0, 0.5, 0.5}}, mesh);
  EXPECT_EQ(band.size(), 21u);  // the diameter along the warp, rim to rim
  const auto quarter = resolve_pins({PinRegion{0.0, 0.5, 0.0, 0.5}}, mesh);
  for (Index v : quarter) EXPECT_TRUE(mesh.is_used(v));
  EXPECT_EQ(pin_error(PinGrid{10, 0}, mesh), "no error");  // the rim on the v = 0 side
}

// The rectangle keeps every cell, in the order (j, i), uses every vertex and spreads the area
// as before: half-width springs along its free edges only.
TEST(DiscCloth, TheRectangleKeepsEveryCell) {
  GridSpec spec;
  spec.nu = 6;
  spec.nv = 4;
  spec.size_u_m = 0.5;
  spec.size_v_m = 0.3;
  const ClothMesh mesh = make_grid(spec);
  EXPECT_EQ(mesh.used_vertex_count(), 24);
  ASSERT_EQ(mesh.quads.size(), 15u);
  std::size_t q = 0;
  for (Index j = 0; j < 3; ++j)
    for (Index i = 0; i < 5; ++i, ++q) {
      EXPECT_TRUE(mesh.has_cell(i, j));
      EXPECT_EQ(mesh.quads[q], (std::array<Index, 4>{mesh.index(i, j), mesh.index(i + 1, j),
                                                     mesh.index(i + 1, j + 1), mesh.index(i, j + 1)}));
    }
  EXPECT_FALSE(mesh.has_cell(5, 0));
  EXPECT_FALSE(mesh.has_cell(0, -1));
  EXPECT_DOUBLE_EQ(mesh.vertex_area_m2.sum(), 0.15);
  EXPECT_DOUBLE_EQ(mesh.vertex_area_m2[mesh.index(0, 0)], 0.25 * 0.1 * 0.1);
  EXPECT_DOUBLE_EQ(mesh.vertex_area_m2[mesh.index(2, 1)], 0.1 * 0.1);
  const MassSpringModel model(mesh, wool());
  // nv·(nu−1) warp + nu·(nv−1) weft edges, two diagonals per cell; (nu−2)·nv + nu·(nv−2) bends.
  EXPECT_EQ(model.springs().size(), 20u + 18u + 30u);
  EXPECT_EQ(model.bends().size(), 16u + 12u);
  const double hu = 0.1, hv = 0.1, G = wool().shear_N_m;
  const double k_inside = (wool().stretch_warp_N_m - G * hu * hu / (hv * hv)) * hv / hu;
  for (const Spring& s : model.springs()) {
    if (s.kind != SpringKind::warp) continue;
    const Index j = s.a / spec.nu;
    EXPECT_DOUBLE_EQ(s.k_N_m, (j == 0 || j == 3) ? 0.5 * k_inside : k_inside) << s.a;
  }
}

}  // namespace
}  // namespace weft::sim
