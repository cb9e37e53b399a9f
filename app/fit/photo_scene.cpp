// A scene from a photo of a cloth held by two corners; see photo_scene.h.

#include "app/fit/photo_scene.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "app/io/input_error.h"

namespace weft::app {
namespace {

namespace fs = std::filesystem;

constexpr double kGravity = 9.81;      // m/s²
constexpr double kPinDrawTime = 0.05;  // s: the right corner reaches its place

double number_at(const nlohmann::json& j, const std::string& file, const std::string& key) {
  if (!j.is_number()) throw InputError(file + ": " + key + ": expected a number");
  return j.get<double>();
}

// {"intrinsics": {...}} of a weft camera (a pose, if any, the identity at the origin).
render::PinholeIntrinsics weft_intrinsics(const nlohmann::json& camera, const std::string& file,
                                          const std::string& where) {
  const nlohmann::json& k = camera.at("intrinsics");
  render::PinholeIntrinsics in;
  const auto get = [&](const char* key) {
    if (!k.contains(key)) throw InputError(file + ": " + where + "intrinsics." + key + ": missing");
    return number_at(k[key], file, where + "intrinsics." + key);
  };
  in.fx_px = get("fx");
  in.fy_px = get("fy");
  in.cx_px = get("cx");
  in.cy_px = get("cy");
  if (!k.contains("size") || !k["size"].is_array() || k["size"].size() != 2)
    throw InputError(file + ": " + where + "intrinsics.size: expected [width, height] in pixels");
  in.width_px = static_cast<int>(number_at(k["size"][0], file, where + "intrinsics.size[0]"));
  in.height_px = static_cast<int>(number_at(k["size"][1], file, where + "intrinsics.size[1]"));
  if (camera.contains("position")) {
    for (int i = 0; i < 3; ++i)
      if (!camera["position"][i].is_number() || camera["position"][i].get<double>() != 0.0)
        throw InputError(file + ": " + where +
                         "position: weft photo-scene's world is the camera's "
                         "frame; give the camera at [0, 0, 0] (or no pose)");
  }
  if (camera.contains("rotation") &&
      camera["rotation"] != nlohmann::json::parse("[[1,0,0],[0,1,0],[0,0,1]]"))
    throw InputError(file + ": " + where +
                     "rotation: weft photo-scene's world is the camera's "
                     "frame; give the identity (or no pose)");
  if (camera.contains("camera_to_world") || camera.contains("world_to_camera"))
    throw InputError(file + ": " + where +
                     "camera_to_world/world_to_camera: weft photo-scene's "
                     "world is the camera's frame; give no pose");
  return in;
}

// R1_scene.json of φ-SfT: (row, column) pairs.
render::PinholeIntrinsics phi_sft_intrinsics(const nlohmann::json& j, const std::string& file) {
  const auto pair = [&](const char* key, bool nested) {
    const nlohmann::json& v = nested ? j.at(key).at(0) : j.at(key);
    if (!v.is_array() || v.size() != 2)
      throw InputError(file + ": " + key + ": expected a (row, column) pair");
    return std::array<double, 2>{number_at(v[0], file, key), number_at(v[1], file, key)};
  };
  const auto f = pair("focal_lengths", true), c = pair("optical_centers", true);
  const auto size = pair("image_size", false);
  for (const char* key : {"camera_positions", "camera_directions"})
    if (j.contains(key)) {
      const nlohmann::json& v = j[key].at(0);
      const bool origin = std::string(key) == "camera_positions";
      const double expect[3] = {0, 0, origin ? 0.0 : 1.0};
      for (int i = 0; i < 3; ++i)
        if (number_at(v.at(i), file, key) != expect[i])
          throw InputError(file + ": " + key +
                           ": weft photo-scene needs the camera at the "
                           "origin looking along +z (its world is the camera's frame)");
    }
  render::PinholeIntrinsics in;
  in.fx_px = f[1];
  in.fy_px = f[0];
  in.cx_px = c[1];
  in.cy_px = c[0];
  in.width_px = static_cast<int>(size[1]);
  in.height_px = static_cast<int>(size[0]);
  return in;
}

std::string metres(double v) {
  char text[48];
  std::snprintf(text, sizeof text, "%.6f m", v);
  return text;
}

nlohmann::json vector_json(const Eigen::Vector3d& v, bool lengths) {
  if (!lengths) return {v.x(), v.y(), v.z()};
  return {metres(v.x()), metres(v.y()), metres(v.z())};
}

}  // namespace

render::PinholeIntrinsics read_photo_camera(const fs::path& path) {
  const std::string file = path.string();
  std::ifstream in(path);
  if (!in) throw InputError(file + ": cannot read the camera file");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file + ": not JSON: " + e.what());
  }
  render::PinholeIntrinsics k;
  try {
    if (j.contains("intrinsics"))
      k = weft_intrinsics(j, file, "");
    else if (j.contains("render") && j["render"].contains("camera") &&
             j["render"]["camera"].contains("intrinsics"))
      k = weft_intrinsics(j["render"]["camera"], file, "render.camera.");
    else if (j.contains("focal_lengths"))
      k = phi_sft_intrinsics(j, file);
    else
      throw InputError(file +
                       ": expected a camera: \"intrinsics\" (a weft camera), "
                       "render.camera.intrinsics (a weft scene) or \"focal_lengths\", "
                       "\"optical_centers\" and \"image_size\" (a φ-SfT scene)");
    render::validate(k);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file + ": " + e.what());
  } catch (const std::invalid_argument& e) {
    throw InputError(file + ": " + e.what());
  }
  return k;
}

namespace {

// The ray direction (x', y', 1) through a pixel of the photo.
Eigen::Vector3d pixel_ray(const render::PinholeIntrinsics& k, const Eigen::Vector2d& px) {
  return {(px.x() - k.cx_px) / k.fx_px, (px.y() - k.cy_px) / k.fy_px, 1.0};
}

}  // namespace

double depth_from_width(const PhotoSceneSetup& s, const std::array<Eigen::Vector2d, 2>& shift_px) {
  const render::PinholeIntrinsics k = s.camera.scaled_to(s.width_px, s.height_px);
  const Eigen::Vector3d a = pixel_ray(k, s.corners_px[0] + shift_px[0]);
  const Eigen::Vector3d b = pixel_ray(k, s.corners_px[1] + shift_px[1]);
  return s.cloth_width_m / (b - a).norm();
}

std::array<Eigen::Vector3d, 2> held_corner_positions(const PhotoSceneSetup& s, const Placement& p) {
  const render::PinholeIntrinsics k = s.camera.scaled_to(s.width_px, s.height_px);
  const double z0 = depth_from_width(s, p.corner_shift_px) * p.depth_scale;
  std::array<Eigen::Vector3d, 2> out;
  for (std::size_t c = 0; c < 2; ++c)
    out[c] = (z0 + (c == 0 ? -0.5 : 0.5) * p.depth_difference_m) *
             pixel_ray(k, s.corners_px[c] + p.corner_shift_px[c]);
  return out;
}

nlohmann::json photo_scene_json(const PhotoSceneSetup& s, const Placement& p,
                                const std::string& description, const std::string& texture_file) {
  const auto corners = held_corner_positions(s, p);
  const Eigen::Vector3d down(0.0, std::cos(p.tilt_rad), std::sin(p.tilt_rad));
  const Eigen::Vector3d span = corners[1] - corners[0];
  const Eigen::Vector3d warp = span.normalized();
  const Eigen::Vector3d weft = -(down - down.dot(warp) * warp).normalized();  // up in the plane
  const Eigen::Vector3d origin = corners[0] - s.cloth_height_m * weft;        // u0v0, bottom left
  const Eigen::Vector3d draw = span - s.cloth_width_m * warp;                 // u1v1's path

  nlohmann::json material = nlohmann::json::object();
  if (!s.material_preset.empty()) material["preset"] = s.material_preset;
  if (p.density_kg_m2) {
    char text[48];
    std::snprintf(text, sizeof text, "%.6g kg/m^2", *p.density_kg_m2);
    material["density"] = text;
  }
  nlohmann::json path = nlohmann::json::array();
  path.push_back({{"time", "0 s"}, {"offset", {"0 m", "0 m", "0 m"}}});
  char time[32];
  std::snprintf(time, sizeof time, "%g s", kPinDrawTime);
  path.push_back({{"time", time}, {"offset", vector_json(draw, true)}});

  const render::PinholeIntrinsics& k = s.camera;
  nlohmann::json render = {
      {"size", {s.width_px, s.height_px}},
      {"camera",
       {{"intrinsics",
         {{"fx", k.fx_px},
          {"fy", k.fy_px},
          {"cx", k.cx_px},
          {"cy", k.cy_px},
          {"size", {k.width_px, k.height_px}}}},
        {"position", {"0 m", "0 m", "0 m"}},
        {"rotation", {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}}},
      {"light", {{"direction", {0.3, -0.5, -1.0}}, {"intensity", 0.8}, {"ambient", 0.3}}},
      {"colors", {{"front", {0.85, 0.8, 0.62}}, {"background", {0, 0, 0}}}},
      {"ground", false},
      // Whatever holds the cloth in the photo is not in its mask: no clips drawn over it.
      {"supports", false},
      {"shading", "lit"},
      {"msaa", 4}};
  if (!texture_file.empty())
    render["texture"] = {{"file", texture_file}, {"mapping", "piece"}};
  nlohmann::json scene;
  scene["description"] = description;
  scene["cloth"] = {{"size", {metres(s.cloth_width_m), metres(s.cloth_height_m)}},
                    {"resolution", {s.resolution[0], s.resolution[1]}},
                    {"origin", vector_json(origin, true)},
                    {"warp_axis", vector_json(warp, false)},
                    {"weft_axis", vector_json(weft, false)},
                    {"material", material},
                    {"pins", {{{"corner", "u0v1"}}, {{"corner", "u1v1"}, {"path", path}}}}};
  scene["simulation"] = {{"model", "mass_spring"},
                         {"integrator", "dynamic_relaxation"},
                         {"gravity", vector_json(kGravity * down, false)},
                         {"time_step", "auto"}};
  scene["output"] = {{"fps", 24}, {"frames", 48}};
  scene["render"] = render;
  return scene;
}

}  // namespace weft::app
