// The cloth's rendering aids applied in one place for both renderers (cloth_surface.h).

#include "render/cloth_surface.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "render/loop_subdivision.h"
#include "render/thickness_shell.h"

namespace weft::render {

void validate(const ClothSurface& surface) {
  const auto fail = [](const std::string& what) {
    throw std::invalid_argument("RenderSettings: cloth_surface." + what);
  };
  if (surface.subdivision_levels < 0 || surface.subdivision_levels > max_subdivision_levels) {
    fail("subdivision_levels must be in 0.." + std::to_string(max_subdivision_levels) + ", got " +
         std::to_string(surface.subdivision_levels));
  }
  if (!(surface.thickness_m >= 0.0) || !std::isfinite(surface.thickness_m))
    fail("thickness_m must be finite and >= 0");
  if (surface.texture.image) {
    if (surface.texture.image->width() < 1 || surface.texture.image->height() < 1)
      fail("texture: the image is empty");
    const Eigen::Vector2d& r = surface.texture.repeat_m;
    if (!(r.minCoeff() > 0.0) || !r.allFinite())
      fail("texture.repeat_m must be finite and > 0 along warp and weft");
  }
  if (!(surface.sheen >= 0.0 && surface.sheen <= 1.0)) fail("sheen must be in [0, 1]");
  if (!(surface.sheen_roughness > 0.0 && surface.sheen_roughness <= 1.0))
    fail("sheen_roughness must be in (0, 1]");
  if (const Weave& weave = surface.weave; weave.normal_map) {
    if (weave.normal_map->width() < 1 || weave.normal_map->height() < 1)
      fail("weave: the normal map is empty");
    if (!(weave.repeat_m.minCoeff() > 0.0) || !weave.repeat_m.allFinite())
      fail("weave.repeat_m must be finite and > 0 along warp and weft");
    if (!(weave.depth >= 0.0 && weave.depth <= 1.0)) fail("weave.depth must be in [0, 1]");
  }
  if (surface.wireframe.enabled) {
    const Wireframe& w = surface.wireframe;
    if (!(w.width_px > 0.0) || !std::isfinite(w.width_px))
      fail("wireframe.width_px must be finite and > 0, got " + std::to_string(w.width_px));
    if (!(w.color.minCoeff() >= 0.0f && w.color.maxCoeff() <= 1.0f))
      fail("wireframe.color must be within 0..1");
  }
}

const RenderMesh& prepare_cloth_mesh(const RenderMesh& mesh, const ClothSurface& surface,
                                     RenderMesh& storage) {
  validate(surface);
  if (surface.subdivision_levels == 0 && surface.thickness_m == 0.0) return mesh;
  storage = loop_subdivide(mesh, surface.subdivision_levels);
  if (surface.thickness_m > 0.0) storage = make_thickness_shell(storage, surface.thickness_m);
  return storage;
}

}  // namespace weft::render
