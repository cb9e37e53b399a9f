// The Embree device and scene owners (embree.h).

#include "base/embree.h"

#include <stdexcept>

namespace weft::base {

EmbreeDevice::EmbreeDevice() : m_device(rtcNewDevice("threads=1")) {
  if (!m_device) {
    throw std::runtime_error("Embree: cannot create a device (error code " +
                             std::to_string(static_cast<int>(rtcGetDeviceError(nullptr))) + ")");
  }
  rtcSetDeviceErrorFunction(m_device, &EmbreeDevice::on_error, this);
}

EmbreeDevice::~EmbreeDevice() {
  rtcReleaseDevice(m_device);
}

void EmbreeDevice::check(const std::string& what) {
  if (m_error.empty()) return;
  const std::string message = m_error;
  m_error.clear();
  throw std::runtime_error("Embree: " + what + ": " + message);
}

void EmbreeDevice::on_error(void* self, RTCError code, const char* message) {
  auto* device = static_cast<EmbreeDevice*>(self);
  if (device->m_error.empty())
    device->m_error = message ? message : "error code " + std::to_string(static_cast<int>(code));
}

EmbreeScene::EmbreeScene(EmbreeDevice& device, RTCBuildQuality quality)
    : m_scene(rtcNewScene(device.get())) {
  device.check("creating a scene");
  if (!m_scene) throw std::runtime_error("Embree: cannot create a scene");
  rtcSetSceneBuildQuality(m_scene, quality);
  device.check("setting the scene's build quality");
}

EmbreeScene::~EmbreeScene() {
  rtcReleaseScene(m_scene);
}

void EmbreeScene::commit(EmbreeDevice& device) {
  rtcCommitScene(m_scene);
  device.check("building the scene's BVH");
}

}  // namespace weft::base
