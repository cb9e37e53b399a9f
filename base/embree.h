#pragma once
// RAII owners of Embree 3's device and scene, for sim's mesh obstacles and render's ray tracer
// alike.

#include <embree3/rtcore.h>

#include <string>

namespace weft::base {

// An Embree device with its error hook installed. Its BVH builds run on one thread, so the tree,
// and with it every query's result, does not depend on any thread count. The hook records the
// first error; check() turns it into std::runtime_error (throwing through Embree's C API is not
// allowed).
class EmbreeDevice {
 public:
  // Throws std::runtime_error when Embree cannot create a device.
  EmbreeDevice();
  ~EmbreeDevice();
  EmbreeDevice(const EmbreeDevice&) = delete;
  EmbreeDevice& operator=(const EmbreeDevice&) = delete;

  RTCDevice get() const { return m_device; }
  // Throws std::runtime_error("Embree: <what>: <message>") if an error was reported since the
  // last check, and forgets it.
  void check(const std::string& what);

 private:
  static void on_error(void* self, RTCError code, const char* message);
  RTCDevice m_device = nullptr;
  std::string m_error;
};

// An Embree scene of `device` (which must outlive it), built at `quality`.
class EmbreeScene {
 public:
  explicit EmbreeScene(EmbreeDevice& device, RTCBuildQuality quality = RTC_BUILD_QUALITY_MEDIUM);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;
  RTCScene get() const { return m_scene; }
  // rtcCommitScene (the BVH build), then device.check().
  void commit(EmbreeDevice& device);

 private:
  RTCScene m_scene = nullptr;
};

}  // namespace weft::base
