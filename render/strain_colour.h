#pragma once
// The false colour of Shading::strain (`weft run --shading strain`), shared by both renderers:
// a diverging map from blue (compressed by the full scale or more) through light grey
// (unstrained) to red (stretched by the full scale or more), after Moreland's "cool to warm"
// map, and its legend, drawn into the frame's top-right corner.

#include <Eigen/Core>
#include <vector>

#include "render/image.h"
#include "render/render_mesh.h"

namespace weft::render {

// Display colour (0..1) of `strain` (length/rest − 1) on a scale of ±full_scale (> 0); values
// beyond the scale take the end colours, NaN the middle one.
Eigen::Vector3f strain_colour(float strain, float full_scale);

// strain_colour of each vertex of `mesh` (all unstrained when its strain is missing).
std::vector<Eigen::Vector3f> strain_colours(const RenderMesh& mesh, float full_scale);

// A vertical colour bar with its title ("strain") and the values of its ends and middle
// ("+5 %", "0", "−5 %"), on a white panel in the image's top-right corner. An image smaller
// than the legend is left as it is.
void draw_strain_legend(Image& image, double full_scale);

}  // namespace weft::render
