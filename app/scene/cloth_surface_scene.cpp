// Scene keys of the cloth's rendering aids (cloth_surface_scene.h).

#include "app/scene/cloth_surface_scene.h"
#include "app/scene/scene_inputs.h"

#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include "app/scene/units.h"
#include "render/image.h"
#include "render/loop_subdivision.h"
#include "render/texture.h"

namespace weft::app {

namespace {

render::WovenCheck read_woven_check(ObjectReader r) {
  render::WovenCheck check;
  check.warp_color = read_color(r, "warp", check.warp_color);
  check.weft_color = read_color(r, "weft", check.weft_color);
  check.ground_color = read_color(r, "ground", check.ground_color);
  check.stripes = static_cast<int>(r.integer("stripes", check.stripes, Range::closed(1, 64)));
  r.finish();
  return check;
}

render::ClothTexture read_texture(ObjectReader r) {
  render::ClothTexture texture;
  const bool has_file = r.has("file"), has_check = r.has("woven_check");
  if (has_file == has_check)
    r.fail("file", "expected exactly one of \"file\" (an image) and \"woven_check\" (an object)");
  if (has_file) {
    const std::filesystem::path file = r.string("file", required);
    const std::filesystem::path path = scene_relative(r.file(), file);
    try {
      texture.image = std::make_shared<const render::Image>(render::read_image(path));
    } catch (const std::exception& e) {
      r.fail("file", "expected a PNG or JPG image: " + std::string(e.what()));
    }
  } else {
    texture.image = std::make_shared<const render::Image>(
        render::make_woven_check(read_woven_check(r.object("woven_check"))));
  }
  texture.mapping = r.enumeration("mapping", render::texture_mapping_names, {texture.mapping});
  if (texture.mapping == render::TextureMapping::piece && r.has("scale"))
    r.fail("scale", "expected no scale with \"mapping\": \"piece\" (the image spans the piece)");
  const auto scale =
      r.quantities("scale", Quantity::length, 2, std::vector<double>{0.1, 0.1}, Range::gt(0.0));
  texture.repeat_m = {scale[0], scale[1]};
  r.finish();
  return texture;
}

// "weave": true (the built-in plain weave's relief at its defaults), false, or an object.
void read_weave(ObjectReader& render, render::Weave& weave) {
  if (render.holds_boolean("weave")) {
    weave.normal_map = render.boolean("weave", required)
                           ? std::make_shared<const render::Image>(render::make_weave_normal_map())
                           : nullptr;
    return;
  }
  ObjectReader r = render.object("weave");
  if (r.has("file")) {
    const std::filesystem::path path = scene_relative(r.file(), r.string("file", required));
    try {
      weave.normal_map = std::make_shared<const render::Image>(render::read_image(path));
    } catch (const std::exception& e) {
      r.fail("file", "expected a PNG or JPG normal map: " + std::string(e.what()));
    }
  } else {
    weave.normal_map = std::make_shared<const render::Image>(render::make_weave_normal_map());
  }
  const auto scale = r.quantities("scale", Quantity::length, 2,
                                  std::vector<double>{weave.repeat_m.x(), weave.repeat_m.y()},
                                  Range::gt(0.0));
  weave.repeat_m = {scale[0], scale[1]};
  weave.depth = r.number("depth", weave.depth, Range::closed(0.0, 1.0));
  r.finish();
}

// "wireframe": true (the defaults), false, or {"width": pixels, "color": [r, g, b]}.
void read_wireframe(ObjectReader& render, render::Wireframe& wireframe) {
  if (render.holds_boolean("wireframe")) {
    wireframe.enabled = render.boolean("wireframe", required);
    return;
  }
  ObjectReader r = render.object("wireframe");
  wireframe.enabled = true;
  wireframe.width_px =
      r.number("width", wireframe.width_px, Range::gt(0.0).le(max_wireframe_width_px));
  wireframe.color = read_color(r, "color", wireframe.color);
  r.finish();
}

}  // namespace

void read_cloth_surface(ObjectReader& render, render::ClothSurface& surface) {
  surface.subdivision_levels = static_cast<int>(render.integer(
      "subdivision", surface.subdivision_levels, Range::closed(0, render::max_subdivision_levels)));
  surface.thickness_m =
      render.quantity("thickness", Quantity::length, surface.thickness_m, Range::ge(0.0));
  if (render.has("texture")) surface.texture = read_texture(render.object("texture"));
  surface.sheen = render.number("sheen", surface.sheen, Range::closed(0.0, 1.0));
  surface.sheen_roughness =
      render.number("sheen_roughness", surface.sheen_roughness, Range::gt(0.0).le(1.0));
  if (render.has("weave")) read_weave(render, surface.weave);
  if (render.has("wireframe")) read_wireframe(render, surface.wireframe);
}

}  // namespace weft::app
