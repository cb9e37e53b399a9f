// What adaptive remeshing buys on a folded sheet, and what CGAL's
// Delaunay refinement costs.
//
// 1. A 1 × 1 m sheet on a uniform 1 cm mesh (20 000 triangles), creased by three parallel
//    folds (Gaussian ridges 3 cm high and 3 cm wide, |κ| up to 67 /m), remeshed with seed 002
//    eq. 29 (c, h_min, h_max below): triangles of the adaptive mesh against a uniform mesh of the
//    same domain at h_min (the size a uniform mesh needs to resolve the folds as finely), and
//    the wall time of each phase.
// 2. The mesher alone at a uniform size giving about 10 000 triangles.
// 3. The curvature estimate's error against h/R: a 30 × 30 cm sheet rolled on a cylinder of
//    radius 10 cm (interior vertices, three rings from the boundary, and all vertices).
// 4. A cloth at rest remeshed, flat and rolled on cylinders, by the linear and the quadratic
//    transfer: the spring energy of its edges
//    before and after, the most negative edge strain after, and the velocities (zero).
// Medians over --repeats runs (default 3); the uniform mesh at h_min (~0.5 M triangles) once.
// --svg FILE draws the adaptive mesh around the middle fold, (u, v) ∈ [0.35, 0.65] × [0, 0.2] m,
// in material coordinates, the old 1 cm mesh's lines in grey under it.
//
// Run: build/bench/remesh_bench [--repeats 3] [--svg FILE]

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iomanip>
#include <string>
#include <vector>

#include "base/timer.h"
#include "sim/remesh/curvature.h"
#include "sim/remesh/mesher.h"
#include "sim/remesh/remesh.h"

namespace {

using namespace weft::sim;
using namespace weft::sim::remesh;

// A size × size sheet of n × n vertices, cells split along one diagonal.
void uniform_sheet(double size, Index n, Matrix2X& material, Triangles& triangles) {
  material.resize(n * n, 2);
  for (Index j = 0; j < n; ++j)
    for (Index i = 0; i < n; ++i) material.row(j * n + i) << size * i / (n - 1), size * j / (n - 1);
  triangles.resize(2 * (n - 1) * (n - 1), 3);
  Index t = 0;
  for (Index j = 0; j + 1 < n; ++j)
    for (Index i = 0; i + 1 < n; ++i) {
      const Index a = j * n + i;
      triangles.row(t++) << a, a + 1, a + n + 1;
      triangles.row(t++) << a, a + n + 1, a + n;
    }
}

// The process's CPU time, ms: less disturbed than wall time by other work on a shared machine
// (everything here runs on one thread).
double cpu_ms() {
  return 1e3 * static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

// The triangles whose centroid lies in the crop [u0, u0 + w] × [0, w·2/3], as SVG polygons,
// 1000 px per 0.3 m.
void svg_triangles(std::ofstream& out, const Matrix2X& x, const Triangles& t, const char* style) {
  const double u0 = 0.35, w = 0.3, scale = 1000.0 / w;
  out << std::fixed << std::setprecision(1) << "<g " << style << ">\n";  // tenths of a pixel
  for (Eigen::Index k = 0; k < t.rows(); ++k) {
    const Vec2 c = (x.row(t(k, 0)) + x.row(t(k, 1)) + x.row(t(k, 2))).transpose() / 3.0;
    if (c.x() < u0 || c.x() > u0 + w || c.y() > w * 2.0 / 3.0) continue;
    out << "<polygon points=\"";
    for (int j = 0; j < 3; ++j)
      out << (x(t(k, j), 0) - u0) * scale << "," << (w * 2.0 / 3.0 - x(t(k, j), 1)) * scale << " ";
    out << "\"/>\n";
  }
  out << "</g>\n";
}

double median(std::vector<double> x) {
  std::sort(x.begin(), x.end());
  return x[x.size() / 2];
}

// Of a mesh made for a uniform size h: the largest and the median longest edge / h, and the
// median mean side / h.
std::array<double, 3> edge_ratios(const MeshResult& mesh, double h) {
  std::vector<double> longest, mean;
  for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) {
    double l = 0.0, sum = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double e = (mesh.material.row(mesh.triangles(t, k)) -
                        mesh.material.row(mesh.triangles(t, (k + 1) % 3)))
                           .norm();
      l = std::max(l, e);
      sum += e;
    }
    longest.push_back(l / h);
    mean.push_back(sum / (3.0 * h));
  }
  return {*std::max_element(longest.begin(), longest.end()), median(longest), median(mean)};
}

// Sum of ½ k (|x_i − x_j| − L_ij)² over the triangle edges (interior ones seen twice, halved),
// k = 1 N/m, L from the material coordinates; and the most negative edge strain.
std::array<double, 2> spring_energy_and_min_strain(const Matrix2X& X, const Triangles& t,
                                                   const Matrix3X& x) {
  double energy = 0.0, min_strain = 0.0;
  for (Eigen::Index k = 0; k < t.rows(); ++k)
    for (int j = 0; j < 3; ++j) {
      const Index a = t(k, j), b = t(k, (j + 1) % 3);
      const double rest = (X.row(a) - X.row(b)).norm();
      const double stretch = (x.row(a) - x.row(b)).norm() - rest;
      energy += 0.25 * stretch * stretch;
      min_strain = std::min(min_strain, stretch / rest);
    }
  return {energy, min_strain};
}

struct BenchOptions {
  int repeats = 3;
  std::string svg_path;  // empty: no drawing
};

// --repeats N and --svg FILE; false for anything else.
bool parse_bench_options(int argc, char** argv, BenchOptions& options) {
  for (int a = 1; a < argc; ++a) {
    if (std::strcmp(argv[a], "--repeats") == 0 && a + 1 < argc) {
      options.repeats = std::max(1, std::atoi(argv[++a]));
    } else if (std::strcmp(argv[a], "--svg") == 0 && a + 1 < argc) {
      options.svg_path = argv[++a];
    } else {
      return false;
    }
  }
  return true;
}

// The 1 × 1 m sheet on its uniform 1 cm mesh, creased by three Gaussian ridges along v, at rest.
RemeshInput folded_sheet() {
  RemeshInput in;
  uniform_sheet(1.0, 101, in.material, in.triangles);
  in.positions.resize(in.material.rows(), 3);
  for (Eigen::Index v = 0; v < in.material.rows(); ++v) {
    const double u = in.material(v, 0);
    double z = 0.0;
    for (double ridge : {0.25, 0.5, 0.75}) z += 0.03 * std::exp(-std::pow((u - ridge) / 0.03, 2));
    in.positions.row(v) << u, in.material(v, 1), z;
  }
  in.velocities = Matrix3X::Zero(in.material.rows(), 3);
  return in;
}

// The adaptive mesh around the middle fold over the old mesh's lines; false if it cannot be
// written.
bool write_fold_svg(const std::string& path, const RemeshInput& in, const RemeshOutput& out) {
  std::ofstream svg(path);
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"1000\" height=\"667\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  svg_triangles(svg, in.material, in.triangles,
                "fill=\"none\" stroke=\"#bbbbbb\" stroke-width=\"3\"");
  svg_triangles(svg, out.mesh.material, out.mesh.triangles,
                "fill=\"none\" stroke=\"#1f4e9c\" stroke-width=\"0.8\"");
  svg << "</svg>\n";
  return static_cast<bool>(svg);
}

// The uniform size of the mesher-alone figure: about 10 000 triangles on the 1 m² sheet.
constexpr double kTenKSize = 0.0225;  // m

// Sections 1 and 2: per repeat, the phase times of the adaptive remesh and the mesher's time
// at kTenKSize; the triangle counts, and from the first repeat the uniform mesh at h_min and
// the shape of the kTenKSize mesh.
struct FoldedSheetFigures {
  std::vector<double> curvature_ms, mesher_ms, transfer_ms, uniform_ms, ten_k_ms, ten_k_cpu_ms;
  std::array<double, 3> ten_k_shape{};
  Eigen::Index adaptive_tris = 0, adaptive_verts = 0, uniform_tris = 0, ten_k_tris = 0;
  double kappa_max = 0.0;
};

// Runs sections 1 and 2 (and draws the SVG on the first repeat when asked); false if the SVG
// cannot be written.
bool measure_folded_sheet(const RemeshInput& in, const RemeshParams& params,
                          const BenchOptions& options, FoldedSheetFigures& f) {
  for (int r = 0; r < options.repeats; ++r) {
    const RemeshOutput out = weft::sim::remesh::remesh(in, params);
    f.curvature_ms.push_back(1e3 * out.curvature_s);
    f.mesher_ms.push_back(1e3 * out.mesher_s);
    f.transfer_ms.push_back(1e3 * out.transfer_s);
    f.adaptive_tris = out.mesh.triangles.rows();
    f.adaptive_verts = out.mesh.material.rows();
    f.kappa_max = out.old_curvature.maxCoeff();
    if (r == 0 && !options.svg_path.empty() && !write_fold_svg(options.svg_path, in, out)) {
      std::fprintf(stderr, "remesh_bench: cannot write %s\n", options.svg_path.c_str());
      return false;
    }

    weft::base::Stopwatch watch;
    if (r == 0) {  // ~0.5 M triangles, tens of seconds: once
      const MeshResult uniform = mesh_domain(in.material, in.triangles, {},
                                             [&](const Vec2&) { return params.size.h_min_m; });
      f.uniform_ms.push_back(watch.milliseconds());
      f.uniform_tris = uniform.triangles.rows();
    }

    watch.restart();
    const double cpu0 = cpu_ms();
    const MeshResult ten_k =
        mesh_domain(in.material, in.triangles, {}, [&](const Vec2&) { return kTenKSize; });
    f.ten_k_ms.push_back(watch.milliseconds());
    f.ten_k_cpu_ms.push_back(cpu_ms() - cpu0);
    f.ten_k_tris = ten_k.triangles.rows();
    if (r == 0) f.ten_k_shape = edge_ratios(ten_k, kTenKSize);
  }
  return true;
}

void print_folded_sheet(const RemeshInput& in, const RemeshParams& params,
                        const FoldedSheetFigures& f, int repeats) {
  std::printf(
      "folded 1 m sheet, 3 folds, max |kappa| estimated %.1f /m; c = %g m, h in [%g, %g] m\n",
      f.kappa_max, params.size.c_m, params.size.h_min_m, params.size.h_max_m);
  std::printf("  old uniform mesh (1 cm):        %8ld triangles\n",
              static_cast<long>(in.triangles.rows()));
  std::printf(
      "  adaptive (eq. 29):              %8ld triangles %7ld vertices; curvature %.1f ms, "
      "mesher %.1f ms, transfer %.1f ms\n",
      static_cast<long>(f.adaptive_tris), static_cast<long>(f.adaptive_verts),
      median(f.curvature_ms), median(f.mesher_ms), median(f.transfer_ms));
  std::printf("  uniform at h_min (%g m):      %8ld triangles; mesher %.1f ms (one run)\n",
              params.size.h_min_m, static_cast<long>(f.uniform_tris), median(f.uniform_ms));
  std::printf("  adaptive / uniform at h_min:    %.3f\n",
              static_cast<double>(f.adaptive_tris) / static_cast<double>(f.uniform_tris));
  std::printf(
      "mesher alone, uniform h = %g m:   %8ld triangles in %.1f ms wall, %.1f ms CPU "
      "(medians of %d)\n",
      kTenKSize, static_cast<long>(f.ten_k_tris), median(f.ten_k_ms), median(f.ten_k_cpu_ms),
      repeats);
  std::printf("  longest edge / h: max %.3f, median %.2f; mean side / h: median %.2f\n",
              f.ten_k_shape[0], f.ten_k_shape[1], f.ten_k_shape[2]);
}

// 4. A cloth at rest remeshed: 30 × 30 cm on 1 cm cells, flat and rolled on cylinders, with
// the folded sheet's size field, by the linear and the quadratic transfer.
void report_remesh_at_rest(const RemeshParams& params) {
  std::printf("at rest, 30 cm sheet on 1 cm cells, remeshed (c = 0.5 mm, h in [3 mm, 5 cm]):\n");
  for (double R : {0.0, 0.1, 0.05, 0.02}) {
    RemeshInput rest;
    uniform_sheet(0.3, 31, rest.material, rest.triangles);
    rest.positions.resize(rest.material.rows(), 3);
    for (Eigen::Index v = 0; v < rest.material.rows(); ++v) {
      const double u = rest.material(v, 0);
      if (R == 0.0) {
        rest.positions.row(v) << u, rest.material(v, 1), 1.0;
      } else {
        rest.positions.row(v) << R * std::sin(u / R), rest.material(v, 1),
            R * (1.0 - std::cos(u / R));
      }
    }
    rest.velocities = Matrix3X::Zero(rest.material.rows(), 3);
    for (const auto transfer : {weft::sim::remesh::PositionTransfer::linear,
                                weft::sim::remesh::PositionTransfer::quadratic}) {
      RemeshParams rest_params = params;
      rest_params.positions = transfer;
      const RemeshOutput out = weft::sim::remesh::remesh(rest, rest_params);
      const auto before =
          spring_energy_and_min_strain(rest.material, rest.triangles, rest.positions);
      const auto after =
          spring_energy_and_min_strain(out.mesh.material, out.mesh.triangles, out.positions);
      std::printf(
          "  R = %-5g m %-9s %6ld triangles; spring energy %.2e -> %.2e J; min edge strain "
          "%.2e; max |v| %.1e m/s\n",
          R, transfer == weft::sim::remesh::PositionTransfer::linear ? "linear" : "quadratic",
          static_cast<long>(out.mesh.triangles.rows()), before[0], after[0], after[1],
          out.velocities.cwiseAbs().maxCoeff());
    }
  }
}

// 3. The curvature estimate on a 30 × 30 cm sheet rolled on a cylinder of radius 10 cm, at
// four resolutions: the largest relative error of |κ| inside (three rings from the boundary)
// and over all vertices.
void report_cylinder_curvature() {
  std::printf("curvature on a cylinder of R = 0.1 m, max relative error of |kappa|:\n");
  for (Index n : {16, 31, 61, 121}) {
    Matrix2X material;
    Triangles triangles;
    uniform_sheet(0.3, n, material, triangles);
    const double R = 0.1;
    Matrix3X x(material.rows(), 3);
    for (Eigen::Index v = 0; v < material.rows(); ++v)
      x.row(v) << R * std::sin(material(v, 0) / R), material(v, 1),
          R * (1.0 - std::cos(material(v, 0) / R));
    const Eigen::VectorXd kappa = vertex_curvature(material, triangles, x);
    double interior = 0.0, all = 0.0;
    for (Index j = 0; j < n; ++j)
      for (Index i = 0; i < n; ++i) {
        const double e = std::abs(kappa(j * n + i) * R - 1.0);
        all = std::max(all, e);
        if (i >= 3 && j >= 3 && i + 3 < n && j + 3 < n) interior = std::max(interior, e);
      }
    std::printf("  h/R = %.3f: interior %.2e, all vertices %.2e\n", 0.3 / (n - 1) / R, interior,
                all);
  }
}

}  // namespace

int main(int argc, char** argv) {
  BenchOptions options;
  if (!parse_bench_options(argc, argv, options)) {
    std::fprintf(stderr, "usage: remesh_bench [--repeats N] [--svg FILE]\n");
    return 2;
  }
  const RemeshInput in = folded_sheet();
  RemeshParams params;
  params.size = {/*c_m=*/5e-4, /*h_min_m=*/0.003, /*h_max_m=*/0.05};
  FoldedSheetFigures figures;
  if (!measure_folded_sheet(in, params, options, figures)) return 1;
  print_folded_sheet(in, params, figures, options.repeats);
  report_remesh_at_rest(params);
  report_cylinder_curvature();
  return 0;
}
