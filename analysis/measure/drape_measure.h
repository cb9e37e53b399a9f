#pragma once
// Drape measurements: the cloth's shadow on the horizontal plane and its area,
// the drape coefficient, the outline radius r(θ) about the support's axis and the fold count.
// Pure functions of positions and triangles; `weft measure` (app/cli/measure_command.h) applies
// them frame by frame. docs/measure.md states the rules and their error bounds.
//
// The drape coefficient follows the Cusick drape test (Cusick 1968, "The measurement of fabric
// drape", J. Textile Inst. 59): the shadow of the draped specimen, less the support, as a share
// of the flat specimen's overhang: DC = (A_shadow − A_support)/(A_specimen − A_support). 0: the
// overhang hangs straight down; 1: it stays flat.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "sim/collision/obstacle.h"
#include "sim/grid.h"
#include "sim/types.h"

namespace weft::analysis {

using Triangles = std::vector<std::array<sim::Index, 3>>;

// The shadow: the vertical projection of the triangles on the horizontal (x, y) plane, as a
// mask on a grid of square cells. A cell belongs to the shadow when its centre lies inside the
// projection of at least one triangle (a fold lying over the sheet counts once: the shadow is
// the union). Exact union areas of thousands of overlapping triangles are costly to compute;
// the raster is simple, and its error has a stated bound (shadow_area_error_bound_m2).
struct ShadowMask {
  double x0_m = 0.0, y0_m = 0.0;  // the low-x, low-y corner of cell (0, 0)
  double cell_m = 0.0;            // side of a cell
  int nx = 0, ny = 0;             // cells along x and y
  std::vector<std::uint8_t> inside;  // #(nx·ny), cell (ix, iy) at iy·nx + ix: 1 in the shadow

  long cell_count() const;  // cells in the shadow
  double area_m2() const { return static_cast<double>(cell_count()) * cell_m * cell_m; }
  sim::Vec2 cell_center_m(int ix, int iy) const {
    return {x0_m + (ix + 0.5) * cell_m, y0_m + (iy + 0.5) * cell_m};
  }
};

// The largest grid rasterize_shadow builds, in cells (2^26: 64 MB of mask).
inline constexpr long max_shadow_cells = 1L << 26;

// Rasterizes the triangles' vertical projection. x: #V×3 positions, m (only the vertices of
// `triangles` are read); cell_m: the cell side, m. A triangle seen edge-on (zero projected
// area: a vertical wall) covers no cell. A cell centre exactly on a projected edge belongs to
// the triangle on its left/upper side only (a half-open rule), so shared edges are not
// double-counted and nothing falls through the cracks. Throws std::invalid_argument for a
// cell_m that is not finite and > 0, a vertex index out of range, a non-finite position, or a
// grid of more than max_shadow_cells cells (choose a coarser cell).
ShadowMask rasterize_shadow(const sim::Matrix3X& x, const Triangles& triangles, double cell_m);

// Bound on |ShadowMask::area_m2() − exact area| for a shadow whose boundary has total length
// perimeter_m and consists of boundary_loops closed curves: only cells the boundary crosses
// can be miscounted, and they lie within a cell diagonal, √2·h, of it; a band of half-width r
// about a closed curve of length P has area at most 2rP + πr² (Steiner's formula for the outer
// half and the inner half bounded by rP). So |error| ≤ 2√2·h·P + 2π·h²·loops.
double shadow_area_error_bound_m2(double perimeter_m, double cell_m, int boundary_loops = 1);

// The specimen's rest area: the sum of its quads' rest areas (a planar quad p0 p1 p2 p3 has
// area |(p2 − p0) × (p3 − p1)|/2), so a specimen that keeps only some grid cells (a disc)
// counts just those. m².
double specimen_rest_area_m2(const sim::ClothMesh& mesh);

// DC = (shadow − support)/(specimen − support), areas in m², dimensionless. Throws
// std::invalid_argument unless all three are finite and ≥ 0 and specimen > support (a specimen
// no larger than its support has no overhang to measure).
double drape_coefficient(double shadow_m2, double support_m2, double specimen_m2);

// What the cloth is draped over, and where its axis is for r(θ).
struct DrapeSupport {
  std::size_t obstacle = 0;  // index in the obstacle list
  std::string kind;          // "cylinder", "box" or "sphere"
  sim::Vec2 axis_m{0.0, 0.0};  // (x, y) of the support's vertical axis
  double top_z_m = 0.0;      // height of its highest point
  double area_m2 = 0.0;      // its horizontal area: the disc, the box's top face, the sphere's great circle
};

// The support of a drape: among the obstacles whose horizontal footprint contains the cloth
// centre's (x, y) and whose top is not above the centre — cylinders with a vertical axis
// (within 1e-6), boxes (any yaw) and spheres; planes, capsules and tilted cylinders are never
// supports — the one with the highest top (the first in list order among equal tops). None:
// nothing holds the cloth from below (a hang). cloth_center_m: e.g. the mean rest position.
std::optional<DrapeSupport> find_support(const std::vector<sim::Obstacle>& obstacles,
                                         const sim::Vec3& cloth_center_m);

// The outline radius r(θ): bin k of `bins` covers angles θ ∈ [2πk/bins, 2π(k+1)/bins) about
// center_m, counter-clockwise from +x, and holds the largest distance from center_m of a shadow
// cell centre in that direction (0 when no cell lies there), m. It underestimates the true
// outline's largest radius over the bin by at most about ρ(1 + √(1 + s²) + s), ρ = h/√2 the
// cells' covering radius (every disc of radius ρ holds a cell centre) and s the outline's slope
// |dr/(r dθ)| there: such a disc fits inside the shadow and the bin ρ√(1 + s²) below a point of
// the outline that lies ρ/r inside the bin's edge (curvature neglected). About 1.7 h on a circle.
// Throws std::invalid_argument for bins < 3.
std::vector<double> outline_radii(const ShadowMask& shadow, const sim::Vec2& center_m, int bins);

// Circular moving average over `window` bins (odd, ≥ 1; 1 returns the input). A box filter of
// width w reduces a wave of period P bins by sinc(w/P) = sin(πw/P)/(πw/P): by 14 % for 12 folds
// with w = 9 of 360 bins. Throws std::invalid_argument for an even or non-positive window or a
// window longer than the signal.
std::vector<double> circular_moving_average(const std::vector<double>& values, int window);

// Peaks of a circular signal with a prominence of at least min_prominence (same unit). A peak
// is a sample, or a run of equal samples, higher than both neighbours; its prominence is its
// height above the higher of the two lowest points between it and the nearest strictly
// higher sample on each side (the lowest point of the whole signal when there is none). A
// constant signal has no peak; a non-constant one has at least its highest. find_peaks gives
// each peak's index (the middle of a run of equal samples), ascending; count_peaks their number.
std::vector<int> find_peaks(const std::vector<double>& values, double min_prominence);
int count_peaks(const std::vector<double>& values, double min_prominence);

// How folds are counted from r(θ): smooth, then count the peaks (a fold is a crest of the wavy
// outline, where the hanging cloth swings outwards) whose prominence is at least
// max(prominence_fraction · (max r − min r), min_prominence_m) of the smoothed outline.
struct FoldCountSettings {
  int smoothing_bins = 9;             // odd; 9° on 360 bins
  double prominence_fraction = 0.1;   // of the smoothed outline's range
  double min_prominence_m = 0.0;      // absolute floor, e.g. 2 raster cells: a near-circle has 0 folds
};

int count_folds(const std::vector<double>& radii_m, const FoldCountSettings& settings);
// The bins of the fold crests count_folds counts, ascending.
std::vector<int> fold_crests(const std::vector<double>& radii_m, const FoldCountSettings& settings);

// The drape of one configuration, all of the above together.
struct DrapeMeasureSettings {
  // Raster cell side as a fraction of √(specimen area): 1e-3 gives 0.5 mm for a 50 cm square.
  // Coarsened if the shadow would need more than max_shadow_cells.
  double cell_fraction = 1e-3;
  int outline_bins = 360;  // 1° bins
  // Folds: min_prominence_m is raised to at least 2 cells, so raster noise on a circle is none.
  FoldCountSettings folds;
};

struct DrapeShape {
  double cell_m = 0.0;            // the raster cell used
  double shadow_m2 = 0.0;         // the shadow's area
  double drape_coefficient = 0.0;
  std::vector<double> radii_m;    // r(θ), outline_bins bins about the support's axis
  int folds = 0;
  std::vector<int> crests;        // the folds' bins in radii_m, ascending (#folds)
};

// The drape measured from a shadow, whatever made it — a simulation's triangles
// (measure_drape) or a top-view photo's silhouette (app/run/drape_photo.h): one ruler. The shadow's
// area, DC against support_m2 and specimen_m2 (drape_coefficient), r(θ) about axis_m
// (outline_radii) and the folds (count_folds, min_prominence_m raised to at least 2 cells).
DrapeShape measure_shadow(const ShadowMask& shadow, const sim::Vec2& axis_m, double support_m2,
                          double specimen_m2, const DrapeMeasureSettings& settings = {});

// Measures the drape of positions x (#V×3, m) of `mesh` over `support`. Throws
// std::invalid_argument when the specimen is no larger than the support (drape_coefficient) or
// a position is not finite.
DrapeShape measure_drape(const sim::ClothMesh& mesh, const Triangles& triangles,
                         const sim::Matrix3X& x, const DrapeSupport& support,
                         const DrapeMeasureSettings& settings = {});

}  // namespace weft::analysis
