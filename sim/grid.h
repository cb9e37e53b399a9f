#pragma once
// The cloth's rest shape and topology (ClothMesh): either a warp/weft quad grid — rectangular,
// or a specimen of another shape (a Cusick drape disc) that keeps only the grid cells inside
// it (make_grid) — or a general triangle mesh, such as one read from a file or a disc meshed
// in rings for a smooth edge (no grid; sim/triangle_cloth.h, sim/round_specimen.h,
// docs/meshes.md).

#include <array>
#include <string>
#include <vector>

#include "base/enum_names.h"
#include "sim/types.h"

namespace weft::sim {

// The specimen cut from the rectangular grid. disc: the ellipse inscribed in the size_u_m ×
// size_v_m rectangle (a circle of diameter size_u_m when the two are equal); a cell is kept
// when its centre lies inside or on the ellipse. The kept area converges to the ellipse's at
// first order in the cell size at worst (every cell the boundary crosses lies within a band
// of half a cell diagonal around it); the in/out errors of those cells largely cancel, and a
// circle measures about order 1.5, irregularly (Gauss's circle problem;
// tests/sim/disc_cloth_test.cpp). No two kept cells meet
// at a corner only (for any ellipse: the parallelogram law), so the kept cells form a
// manifold mesh.
enum class SpecimenShape { rectangle, disc };

inline constexpr base::EnumNames<SpecimenShape, 2> specimen_shape_names{
    {{SpecimenShape::rectangle, "rectangle"}, {SpecimenShape::disc, "disc"}}};

// The edge of a disc. staircase: the grid's cells inside the ellipse, above (a warp/weft grid).
// smooth: the ellipse meshed in concentric rings of triangles whose outer ring lies on it
// (make_round_specimen, sim/round_specimen.h): a triangle mesh without a grid.
enum class DiscEdge { staircase, smooth };

inline constexpr base::EnumNames<DiscEdge, 2> disc_edge_names{
    {{DiscEdge::staircase, "staircase"}, {DiscEdge::smooth, "smooth"}}};

struct GridSpec {
  double size_u_m = 1.0, size_v_m = 1.0;  // extent along warp (u) and weft (v); the disc's diameters
  SpecimenShape shape = SpecimenShape::rectangle;
  DiscEdge disc_edge = DiscEdge::staircase;  // a disc's edge; a rectangle's must be staircase
  Index nu = 32, nv = 32;                 // vertices along warp and weft, each ≥ 2; a smooth
                                          // disc takes its ring count from them (round_specimen_rings)
  Vec3 origin{0.0, 0.0, 1.0};             // world position of material point (0, 0)
  Vec3 warp_axis{1.0, 0.0, 0.0};          // unit world direction of +u
  Vec3 weft_axis{0.0, 1.0, 0.0};          // unit world direction of +v, orthogonal to warp_axis
};

// Vertex (i, j) — i along warp, j along weft — has index j·nu + i, for every vertex of the
// rectangular grid. Cell (i, j) is the grid square with corners (i, j) and (i+1, j+1); `quads`
// holds the kept cells only. A vertex of no kept cell is unused: it has no area (so no mass),
// no forces or constraints act on it, the simulator never moves it, and it is neither drawn
// nor counted in the diagnostics. A rectangle keeps every cell and uses every vertex.
//
// A mesh without a grid (has_grid() false: nu = nv = 0, no quads, no cells) is given by its
// triangles (`faces`), each counter-clockwise about warp×weft in material coordinates; every
// vertex is a corner of one. The grid's accessors (index, has_cell, the edge counts) are for
// grid meshes only; what needs the grid checks has_grid() and says so.
struct ClothMesh {
  Index nu = 0, nv = 0;                        // 0 × 0: no grid
  // #V×3, metres: the rest shape, the flat pattern laid in space (material point (u, v) at
  // origin + u·warp_axis + v·weft_axis); the simulation starts here unless start_positions.
  Matrix3X rest_positions;
  std::vector<Vec2> material_coords;           // #V (u, v), metres; u along the warp
  std::vector<std::array<Index, 4>> quads;     // #Q kept cells, row by row, counter-clockwise about warp×weft: (i,j) (i+1,j) (i+1,j+1) (i,j+1)
  std::vector<std::array<Index, 3>> faces;     // a mesh without a grid: its triangles
  Matrix3X start_positions;                    // #V×3 where the simulation starts, or empty: at rest
  std::string source;                          // where it came from (a file), for messages; "" for a built-in grid
  Eigen::VectorXd vertex_area_m2;              // #V lumped (area-weighted) area per vertex, 0 if unused
  std::vector<bool> cell_kept;                 // #(nu−1)(nv−1): cell (i, j) at j·(nu−1) + i
  std::vector<bool> vertex_used;               // #V: a corner of at least one kept cell

  Index vertex_count() const { return static_cast<Index>(rest_positions.rows()); }
  bool has_grid() const { return nu > 0 && nv > 0; }
  // "the cloth mesh panel.obj" or "the cloth", for messages about what a mesh lacks.
  std::string name() const { return source.empty() ? "the cloth" : "the cloth mesh " + source; }
  // Throws std::invalid_argument "<what> needs the cloth's warp/weft grid; <name()> has none
  // (a triangle mesh; docs/meshes.md)" when the mesh has no grid.
  void require_grid(const std::string& what) const;
  Index index(Index i, Index j) const { return j * nu + i; }
  // Whether cell (i, j) is kept; false outside the grid (i ∉ [0, nu−2] or j ∉ [0, nv−2]).
  bool has_cell(Index i, Index j) const {
    return i >= 0 && j >= 0 && i + 1 < nu && j + 1 < nv &&
           cell_kept[static_cast<std::size_t>(j * (nu - 1) + i)];
  }
  // How many kept cells (0, 1 or 2) have the warp edge (i,j)–(i+1,j), resp. the weft edge
  // (i,j)–(i,j+1), as a side. An edge exists when this is at least 1; 1 marks a free edge.
  int warp_edge_cells(Index i, Index j) const { return has_cell(i, j - 1) + has_cell(i, j); }
  int weft_edge_cells(Index i, Index j) const { return has_cell(i - 1, j) + has_cell(i, j); }
  bool is_used(Index v) const { return vertex_used[static_cast<std::size_t>(v)]; }
  Index used_vertex_count() const;
  // Two triangles per quad, split along the (i,j)–(i+1,j+1) diagonal, same orientation as
  // quads; a mesh without a grid: its faces.
  std::vector<std::array<Index, 3>> triangles() const;
  // Where the simulation starts: start_positions, or rest_positions when that is empty.
  const Matrix3X& start() const { return start_positions.rows() ? start_positions : rest_positions; }
};

// The cloth spec describes: the grid keeping the cells of spec.shape, or for a disc with a
// smooth edge its ring mesh (make_round_specimen; no grid). Throws std::invalid_argument for a
// resolution below 2 × 2, a size that is not positive and finite, or a smooth rectangle.
// Throws std::invalid_argument unless the resolution is at least 2 × 2 and the size positive
// and finite (make_grid and make_round_specimen check it first).
void check_grid_spec(const GridSpec& spec);
ClothMesh make_grid(const GridSpec& spec);
// The grid of spec's size, resolution and placement keeping the cells flagged in `cells`
// (#(nu−1)(nv−1), cell (i, j) at j·(nu−1) + i) whatever spec.shape says: a grid recognised in
// a mesh file (sim/triangle_cloth.h).
ClothMesh make_grid_cells(const GridSpec& spec, const std::vector<bool>& cells);

}  // namespace weft::sim
