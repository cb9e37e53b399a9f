// Rotation-free triangles (seed 002, Zhou & Sze): RFT bending, RFT3 and RFT6 membranes.
// Derivatives against finite differences, rigid-motion invariance, membrane patch tests,
// cylindrical bending against ½ B κ² (warp, weft, oblique), the free-edge condition, and the
// two RFT3/RFT6 differences: the sharp fold of seed 002 Fig. 3 and in-plane bending.

#include "sim/rft/rft.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

#include "base/constants.h"
#include "sim/grid.h"
#include "sim/material/material.h"
#include "sim/rft/rft_bending.h"
#include "sim/rft/rft_membrane.h"
#include "tests/sim/force_term_fd.h"

namespace weft::sim {
namespace {

using fd::expect_assembled_stiffness_matches_forces;
using fd::expect_forces_match_energy;
using fd::perturbed;
using fd::smallest_eigenvalue;

Material fabric() {
  return fd::anisotropic_fabric();
}

ClothMesh sheet(Index nu, Index nv, double size_u_m, double size_v_m) {
  return fd::flat_sheet(nu, nv, size_u_m, size_v_m);
}

// Positions x(u, v) of every vertex from its material coordinates.
Matrix3X deformed(const ClothMesh& mesh, const std::function<Vec3(const Vec2&)>& map) {
  Matrix3X x(mesh.vertex_count(), 3);
  for (Index i = 0; i < mesh.vertex_count(); ++i)
    x.row(i) = map(mesh.material_coords[static_cast<std::size_t>(i)]).transpose();
  return x;
}

double total_area(const ClothMesh& mesh) {
  return (mesh.material_coords.back() - mesh.material_coords.front()).prod();
}

std::vector<RftPatch> one_patch(const ClothMesh& mesh, int size) {
  for (const RftPatch& p : make_rft_patches(mesh))
    if (p.size == size) return {p};
  ADD_FAILURE() << "no patch of size " << size;
  return {};
}

Mat3 rotation(double angle_rad, const Vec3& axis) {
  return Eigen::AngleAxisd(angle_rad, axis.normalized()).toRotationMatrix();
}

TEST(RftPatches, NeighboursSitAcrossEachEdgeAtTheParallelogramPoint) {
  const ClothMesh mesh = sheet(5, 4, 0.4, 0.3);
  const auto patches = make_rft_patches(mesh);
  ASSERT_EQ(patches.size(), mesh.triangles().size());
  int counts[7] = {};
  for (const RftPatch& p : patches) {
    ++counts[p.size];
    for (int k = 0; k < 3; ++k) {
      const int s = p.opposite_slot[static_cast<std::size_t>(k)];
      if (s < 0) continue;
      const auto uv = rft_patch_material_coords(mesh, p);
      // On the grid the opposite vertex is the point reflection of t_k through the edge.
      const Vec2 expected = uv[static_cast<std::size_t>((k + 1) % 3)] +
                            uv[static_cast<std::size_t>((k + 2) % 3)] -
                            uv[static_cast<std::size_t>(k)];
      EXPECT_LT((uv[static_cast<std::size_t>(s)] - expected).norm(), 1e-12);
    }
  }
  // 4×3 quads: boundary edges 2·(4 + 3) = 14, each removing one neighbour from one triangle;
  // two corner triangles lose two.
  EXPECT_EQ(counts[4], 2);
  EXPECT_EQ(counts[5], 10);
  EXPECT_EQ(counts[6], 24 - 12);
}

TEST(RftBending, ForcesMatchEnergyAtPerturbedConfigurations) {
  const ClothMesh mesh = sheet(5, 4, 0.2, 0.12);
  const auto term = make_rft_bending(mesh, fabric());
  for (unsigned seed : {1u, 2u, 3u})
    expect_forces_match_energy(*term, perturbed(mesh.rest_positions, 0.015, seed));
}

TEST(RftBending, StiffnessIsTheExactConstantPsdHessian) {
  const ClothMesh mesh = sheet(5, 4, 0.2, 0.12);
  for (int size : {6, 5, 4}) {  // interior, free-edge and corner patches
    const RftBending term(mesh, fabric(), one_patch(mesh, size));
    const Matrix3X x = perturbed(mesh.rest_positions, 0.02, 7u + static_cast<unsigned>(size));
    expect_assembled_stiffness_matches_forces(term, x);
    ElementMatrix K, K_rest, K_psd;
    term.element_stiffness(x, 0, K, false);
    term.element_stiffness(mesh.rest_positions, 0, K_rest, false);
    term.element_stiffness(x, 0, K_psd, true);
    EXPECT_EQ((K - K_rest).cwiseAbs().maxCoeff(), 0.0) << "the RFT bending stiffness is constant";
    EXPECT_EQ((K - K_psd).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_GE(smallest_eigenvalue(K), -1e-12 * K.cwiseAbs().maxCoeff());
  }
}

TEST(RftMembrane, ForcesMatchEnergyAtPerturbedConfigurations) {
  const ClothMesh mesh = sheet(5, 4, 0.2, 0.12);
  for (RftMembrane kind : {RftMembrane::three_node, RftMembrane::six_node}) {
    const auto term = make_rft_membrane(mesh, fabric(), kind);
    for (unsigned seed : {1u, 2u, 3u})
      expect_forces_match_energy(*term, perturbed(mesh.rest_positions, 0.01, seed));
  }
}

TEST(RftMembrane, StiffnessIsTheExactHessianAndItsProjectionIsPsd) {
  const ClothMesh mesh = sheet(5, 4, 0.2, 0.12);
  for (RftMembrane kind : {RftMembrane::three_node, RftMembrane::six_node}) {
    for (int size : {6, 5, 4}) {
      SCOPED_TRACE(::testing::Message()
                   << (kind == RftMembrane::six_node ? "RFT6" : "RFT3") << ", patch of " << size);
      const RftMembraneTerm term(mesh, fabric(), kind, one_patch(mesh, size));
      expect_assembled_stiffness_matches_forces(
          term, perturbed(mesh.rest_positions, 0.01, 11u + static_cast<unsigned>(size)));
      // Compressed and sheared: the exact Hessian is indefinite, the projection is not.
      const Matrix3X squeezed = perturbed(0.8 * mesh.rest_positions, 0.002, 5u);
      ElementMatrix K, K_psd;
      term.element_stiffness(squeezed, 0, K, false);
      term.element_stiffness(squeezed, 0, K_psd, true);
      EXPECT_LT(smallest_eigenvalue(K), -1e-6 * K.cwiseAbs().maxCoeff());
      EXPECT_GE(smallest_eigenvalue(K_psd), -1e-9 * K_psd.cwiseAbs().maxCoeff());
      // Uniformly stretched without shear (all strains ≥ 0): projection changes nothing.
      const Matrix3X stretched =
          deformed(mesh, [](const Vec2& uv) { return Vec3(1.03 * uv.x(), 1.02 * uv.y(), 0.0); });
      term.element_stiffness(stretched, 0, K, false);
      term.element_stiffness(stretched, 0, K_psd, true);
      EXPECT_LE((K - K_psd).cwiseAbs().maxCoeff(), 1e-9 * K.cwiseAbs().maxCoeff());
    }
  }
}

// Rest shape moved rigidly (translation and a finite rotation): no energy, no force.
TEST(Rft, RigidMotionsStoreNoEnergyAndExertNoForce) {
  const ClothMesh mesh = sheet(6, 5, 0.25, 0.2);
  const Mat3 R = rotation(1.1, Vec3(1.0, 2.0, 3.0));
  const Vec3 t(3.0, -2.0, 5.0);
  const Matrix3X moved =
      deformed(mesh, [&](const Vec2& uv) { return Vec3(R * Vec3(uv.x(), uv.y(), 0.0) + t); });
  // Reference scales: 1 % warp stretch, and a bend of radius 1 m.
  const Matrix3X stretched =
      deformed(mesh, [](const Vec2& uv) { return Vec3(1.01 * uv.x(), uv.y(), 0.0); });
  const Matrix3X bent = deformed(
      mesh, [](const Vec2& uv) { return Vec3(std::sin(uv.x()), uv.y(), 1.0 - std::cos(uv.x())); });
  struct Case {
    std::unique_ptr<ForceTerm> term;
    const Matrix3X* reference;
  };
  std::vector<Case> cases;
  cases.push_back({make_rft_bending(mesh, fabric()), &bent});
  cases.push_back({make_rft_membrane(mesh, fabric(), RftMembrane::three_node), &stretched});
  cases.push_back({make_rft_membrane(mesh, fabric(), RftMembrane::six_node), &stretched});
  for (const Case& c : cases) {
    const double e_ref = c.term->energy(*c.reference);
    Matrix3X f_ref = Matrix3X::Zero(mesh.vertex_count(), 3), f = f_ref;
    c.term->add_forces(*c.reference, f_ref);
    c.term->add_forces(moved, f);
    EXPECT_GT(e_ref, 0.0);
    EXPECT_LE(std::abs(c.term->energy(mesh.rest_positions)), 1e-12 * e_ref) << c.term->describe();
    EXPECT_LE(std::abs(c.term->energy(moved)), 1e-12 * e_ref) << c.term->describe();
    EXPECT_LE(f.cwiseAbs().maxCoeff(), 1e-9 * f_ref.cwiseAbs().maxCoeff()) << c.term->describe();
  }
}

// Homogeneous Green strain, exactly: a warp or weft stretch with ε_uu (or ε_vv) = ε, and a
// pure shear with γ = 2 ε_uv, composed with a rotation. Both membranes reproduce any affine
// map, so E = ½ Y ε² A and ½ G γ² A to rounding.
TEST(RftMembrane, UniformStretchAndShearGiveTheContinuumEnergy) {
  const ClothMesh mesh = sheet(6, 5, 0.3, 0.2);
  const Material mat = fabric();
  const double area = total_area(mesh), eps = 0.05, gamma = 0.1;
  const Mat3 R = rotation(0.7, Vec3(0.3, -1.0, 0.5));
  const double lambda = std::sqrt(1.0 + 2.0 * eps);
  const double a = 0.5 * (std::sqrt(1.0 + gamma) + std::sqrt(1.0 - gamma));
  const double b =
      0.5 * (std::sqrt(1.0 + gamma) - std::sqrt(1.0 - gamma));  // [a b; b a]² = [1 γ; γ 1]
  const auto map = [&](double fuu, double fuv, double fvu, double fvv) {
    return deformed(mesh, [=](const Vec2& uv) {
      return Vec3(R * Vec3(fuu * uv.x() + fuv * uv.y(), fvu * uv.x() + fvv * uv.y(), 0.0));
    });
  };
  for (RftMembrane kind : {RftMembrane::three_node, RftMembrane::six_node}) {
    const auto term = make_rft_membrane(mesh, mat, kind);
    const double warp = term->energy(map(lambda, 0.0, 0.0, 1.0));
    const double weft = term->energy(map(1.0, 0.0, 0.0, lambda));
    const double shear = term->energy(map(a, b, b, a));
    EXPECT_NEAR(warp, 0.5 * mat.stretch_warp_N_m * eps * eps * area, 1e-10 * warp)
        << term->describe();
    EXPECT_NEAR(weft, 0.5 * mat.stretch_weft_N_m * eps * eps * area, 1e-10 * weft)
        << term->describe();
    EXPECT_NEAR(shear, 0.5 * mat.shear_N_m * gamma * gamma * area, 1e-10 * shear)
        << term->describe();
  }
}

// The sheet wrapped onto a cylinder of radius R, its curvature κ = 1/R along the warp (or the
// weft). Relative error of the total energy against ½ B κ² × area, and of the interior
// triangles' energy per area.
struct CylinderResult {
  double total_error, interior_error;
};

CylinderResult cylinder_error(Index n, bool along_warp, const Material& mat) {
  const double R = 0.5;
  const ClothMesh mesh = sheet(n, n, 1.0, 1.0);
  const Matrix3X x = deformed(mesh, [&](const Vec2& uv) {
    const double s = along_warp ? uv.x() : uv.y(), t = along_warp ? uv.y() : uv.x();
    const Vec3 p(R * std::sin(s / R), t, R * (1.0 - std::cos(s / R)));
    return along_warp ? p : Vec3(p.y(), p.x(), p.z());
  });
  const RftBending term(mesh, mat, make_rft_patches(mesh));
  const double B = along_warp ? mat.bend_warp_Nm : mat.bend_weft_Nm;
  const double density = 0.5 * B / (R * R);  // J/m²
  double interior_energy = 0.0, interior_area = 0.0;
  for (std::size_t e = 0; e < term.patches().size(); ++e) {
    if (term.patches()[e].size < 6) continue;
    interior_energy +=
        rft_bending_energy(term.rest()[e], term.rigidity(), rft_gather(x, term.patches()[e]));
    interior_area += term.rest()[e].area_m2;
  }
  return {term.energy(x) / (density * total_area(mesh)) - 1.0,
          interior_energy / (density * interior_area) - 1.0};
}

TEST(RftBending, CylinderEnergyConvergesToHalfBKappaSquaredAlongWarpAndWeft) {
  const Material mat = fabric();
  for (bool along_warp : {true, false}) {
    double previous = 1.0;
    for (Index n : {11, 21, 41, 81}) {
      const CylinderResult r = cylinder_error(n, along_warp, mat);
      std::printf(
          "[ RFT      ] cylinder R = 0.5 m along %s, %d×%d: total %+.3f %%, interior %+.4f %%\n",
          along_warp ? "warp" : "weft", n, n, 100.0 * r.total_error, 100.0 * r.interior_error);
      // The free edges across the bend hold no curvature (κ_nn = 0): a deficit of one
      // boundary triangle per row, h/L of the area.
      EXPECT_LT(r.total_error, 0.0);
      EXPECT_LT(std::abs(r.total_error), previous);
      EXPECT_NEAR(r.total_error, -1.0 / static_cast<double>(n - 1),
                  0.3 / static_cast<double>(n - 1));
      EXPECT_LT(std::abs(r.interior_error), 0.01);
      previous = std::abs(r.total_error);
    }
    EXPECT_LT(previous, 0.02);
  }
}

// Curvature κ along the direction at θ to the warp, interior triangles only: the energy per area
// is ½ B(θ) κ² with B(θ) = (√B_warp cos²θ + √B_weft sin²θ)² (rft_bending_kernel.h).
TEST(RftBending, ObliqueCylinderHasTheOrthotropicRigidity) {
  const Material mat = fabric();
  const double R = 0.5;
  const ClothMesh mesh = sheet(31, 31, 1.0, 1.0);
  for (double theta_deg : {30.0, 45.0, 75.0}) {
    const double c = std::cos(theta_deg * base::kPi / 180.0), s = std::sin(theta_deg * base::kPi / 180.0);
    const Matrix3X x = deformed(mesh, [&](const Vec2& uv) {
      const double along = c * uv.x() + s * uv.y(), across = -s * uv.x() + c * uv.y();
      const double a = R * std::sin(along / R);
      return Vec3(c * a - s * across, s * a + c * across, R * (1.0 - std::cos(along / R)));
    });
    const RftBending term(mesh, mat, make_rft_patches(mesh));
    double energy = 0.0, area = 0.0;
    for (std::size_t e = 0; e < term.patches().size(); ++e) {
      if (term.patches()[e].size < 6) continue;
      energy +=
          rft_bending_energy(term.rest()[e], term.rigidity(), rft_gather(x, term.patches()[e]));
      area += term.rest()[e].area_m2;
    }
    const double root = std::sqrt(mat.bend_warp_Nm) * c * c + std::sqrt(mat.bend_weft_Nm) * s * s;
    EXPECT_NEAR(energy / area, 0.5 * root * root / (R * R), 0.005 * energy / area)
        << theta_deg << "°";
  }
}

// Free edges: the fit of a boundary patch has no curvature normal to the free edge, and still
// reproduces every quadratic whose normal curvature is zero (e.g. bending along the edge).
TEST(RftBending, FreeEdgeHasNoNormalCurvatureAndKeepsTheTangentialOne) {
  const ClothMesh mesh = sheet(5, 4, 0.2, 0.12);
  int boundary_edges = 0;
  for (const RftPatch& p : make_rft_patches(mesh)) {
    const auto uv = rft_patch_material_coords(mesh, p);
    const RftBendingRest r = rft_bending_rest(uv, p.opposite_slot);
    ASSERT_TRUE(r.ok);
    for (int k = 0; k < 3; ++k) {
      if (p.opposite_slot[static_cast<std::size_t>(k)] >= 0) continue;
      ++boundary_edges;
      const Vec2 t =
          (uv[static_cast<std::size_t>((k + 2) % 3)] - uv[static_cast<std::size_t>((k + 1) % 3)])
              .normalized();
      const Vec2 n(-t.y(), t.x());
      // κ_nn = n_u² w_uu + n_v² w_vv + n_u n_v (2 w_uv), as an operator on nodal values.
      const auto kappa_nn =
          n.x() * n.x() * r.L.row(0) + n.y() * n.y() * r.L.row(1) + n.x() * n.y() * r.L.row(2);
      EXPECT_LE(kappa_nn.cwiseAbs().maxCoeff(), 1e-9 * r.L.cwiseAbs().maxCoeff());
    }
    // A quadratic height w with zero normal curvature on every free edge of the patch:
    // bending along the free edge (one free edge), or pure twist w = τ u v (corner, free edges
    // along warp and weft). Its curvature is reproduced exactly.
    ASSERT_GE(p.size, 4);
    Vec2 t = Vec2::Zero();
    for (int k = 0; k < 3; ++k)
      if (p.opposite_slot[static_cast<std::size_t>(k)] < 0)
        t = (uv[static_cast<std::size_t>((k + 2) % 3)] - uv[static_cast<std::size_t>((k + 1) % 3)])
                .normalized();
    const double kappa_per_m = 3.0;
    RftPatchPositions X = RftPatchPositions::Zero();
    Eigen::Vector3d expected;  // (w_uu, w_vv, 2 w_uv)
    for (int i = 0; i < p.size; ++i) {
      const Vec2& q = uv[static_cast<std::size_t>(i)];
      X(2, i) =
          p.size == 4 ? kappa_per_m * q.x() * q.y() : 0.5 * kappa_per_m * std::pow(t.dot(q), 2);
    }
    if (p.size == 4)
      expected = Eigen::Vector3d(0.0, 0.0, 2.0 * kappa_per_m);
    else if (p.size == 5)
      expected = kappa_per_m * Eigen::Vector3d(t.x() * t.x(), t.y() * t.y(), 2.0 * t.x() * t.y());
    else
      continue;
    const Eigen::Vector3d kappa = rft_curvature_vectors(r, X).row(2).transpose();
    EXPECT_LE((kappa - expected).cwiseAbs().maxCoeff(), 1e-9) << "patch of " << p.size;
  }
  EXPECT_EQ(boundary_edges, 2 * (4 + 3));
}

// Seed 002 §3, Fig. 3: the vertex across one edge of a triangle folds about that edge (lengths
// to the edge's ends kept) by the angle φ (the paper's θ = π − φ); 1 cm spacing, Kang & Yu
// wool. The triangle itself does not move, so RFT3's (CST) membrane energy is zero, while the
// six-node interpolation compresses the mid-edge across the fold: at that mid-edge
// F n = ½ (n + R_φ n), so ε_nn = −½ sin²(φ/2), and the triangle's averaged strain is a third
// of it. The RFT bending energy of the fold only grows as sin²(φ/2) (it saturates at φ = π),
// which is why RFT3 admits sharp folds (Fig. 1) and RFT6 does not.
TEST(RftMembrane, SharpFoldOfSeed002Fig3LoadsOnlyTheSixNodeMembrane) {
  const double h = 0.01;
  const ClothMesh mesh = sheet(4, 4, 3 * h, 3 * h);
  const Material wool;  // Kang & Yu (seed 002 §4), the default
  const auto patches = make_rft_patches(mesh);
  // The lower triangle of the centre quad: (1,1) (2,1) (2,2); edge 1–2 is the line u = 2h, whose
  // normal is the warp; across it lies (3,2).
  const RftPatch* centre = nullptr;
  for (const RftPatch& p : patches)
    if (p.size == 6 && p.vertices[0] == mesh.index(1, 1) && p.vertices[1] == mesh.index(2, 1))
      centre = &p;
  ASSERT_NE(centre, nullptr);
  const int p0 = centre->opposite_slot[0];
  ASSERT_EQ(centre->vertices[static_cast<std::size_t>(p0)], mesh.index(3, 2));
  const auto uv = rft_patch_material_coords(mesh, *centre);
  const RftMembraneRest m3 = rft3_membrane_rest(uv),
                        m6 = rft6_membrane_rest(uv, centre->opposite_slot);
  const RftBendingRest b = rft_bending_rest(uv, centre->opposite_slot);
  const RftMembraneRigidity Dm{wool.stretch_warp_N_m, wool.stretch_weft_N_m, wool.shear_N_m};
  const RftBendingRigidity Db = rft_bending_rigidity(wool.bend_warp_Nm, wool.bend_weft_Nm);
  const double area = b.area_m2;
  double bend_90 = 0.0;
  for (double phi_deg : {10.0, 30.0, 60.0, 90.0, 135.0, 180.0}) {
    const double phi = phi_deg * base::kPi / 180.0;
    RftPatchPositions X = rft_gather(mesh.rest_positions, *centre);
    X.col(p0) = Vec3(2 * h + h * std::cos(phi), 2 * h, h * std::sin(phi));
    const double e3 = rft_membrane_energy(m3, Dm, X), e6 = rft_membrane_energy(m6, Dm, X);
    const double eb = rft_bending_energy(b, Db, X);
    const double s2 = std::pow(std::sin(phi / 2), 2);
    std::printf(
        "[ RFT      ] fold φ = %5.1f° (θ = %5.1f°): per area, bending %.4g, RFT3 membrane %.3g, "
        "RFT6 membrane %.4g J/m²\n",
        phi_deg, 180.0 - phi_deg, eb / area, e3 / area, e6 / area);
    EXPECT_LE(e3, 1e-20);
    EXPECT_NEAR(e6, 0.5 * area * wool.stretch_warp_N_m * std::pow(s2 / 6.0, 2), 1e-9 * e6);
    if (phi_deg == 90.0) bend_90 = eb;
    if (phi_deg == 180.0) {
      EXPECT_NEAR(eb, 2.0 * bend_90, 1e-9 * eb) << "RFT bending saturates as sin²(φ/2)";
      EXPECT_GT(e6, 10.0 * eb) << "a full fold costs mostly six-node membrane energy";
    }
  }
}

// In-plane bending of a strip (length 10 cm, width 2 cm, two triangles across): the strip is
// bent in its plane to radius R, so the exact Green strain ε_uu = y/R + y²/(2R²) varies across
// the width (y from the centre line) and there is no shear. The CST's piecewise-constant strain
// overestimates ∫ ε² (and adds spurious shear): RFT3 is over-stiff; RFT6's mid-edge strains are
// closer to the continuum energy ½ Y_u ∫ ε_uu² dA.
TEST(RftMembrane, InPlaneBendingRft3IsOverStiffRft6IsCloser) {
  const double L = 0.1, W = 0.02, R = 0.5;
  const ClothMesh mesh = sheet(21, 3, L, W);
  const Material mat = fabric();
  const Matrix3X x = deformed(mesh, [&](const Vec2& uv) {
    const double y = uv.y() - 0.5 * W;
    return Vec3((R + y) * std::sin(uv.x() / R), -R + (R + y) * std::cos(uv.x() / R), 0.0);
  });
  const double c = 0.5 * W;  // ∫_{−c}^{c} (y/R + y²/2R²)² dy
  const double exact =
      0.5 * mat.stretch_warp_N_m * L *
      (2.0 * std::pow(c, 3) / (3.0 * R * R) + 2.0 * std::pow(c, 5) / (20.0 * std::pow(R, 4)));
  const double e3 = make_rft_membrane(mesh, mat, RftMembrane::three_node)->energy(x);
  const double e6 = make_rft_membrane(mesh, mat, RftMembrane::six_node)->energy(x);
  std::printf("[ RFT      ] in-plane bending: RFT3 / exact = %.3f, RFT6 / exact = %.3f\n",
              e3 / exact, e6 / exact);
  EXPECT_GT(e3, 1.2 * exact);
  EXPECT_LT(std::abs(e6 - exact), std::abs(e3 - exact));
}

TEST(Rft, RejectsNegativeRigidityNamingTheField) {
  const ClothMesh mesh = sheet(3, 3, 0.1, 0.1);
  Material mat = fabric();
  mat.bend_weft_Nm = -1.0;
  try {
    make_rft_bending(mesh, mat);
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("material.bend_weft_Nm"), std::string::npos) << e.what();
  }
  mat = fabric();
  mat.shear_N_m = std::nan("");
  EXPECT_THROW(make_rft_membrane(mesh, mat, RftMembrane::six_node), std::invalid_argument);
}

}  // namespace
}  // namespace weft::sim
