// The Embree owners: a device and scene come up, an empty scene commits, and an error reported
// through the hook becomes an exception naming what was being done.

#include "base/embree.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace weft::base {
namespace {

TEST(Embree, DeviceAndSceneCommit) {
  EmbreeDevice device;
  ASSERT_NE(device.get(), nullptr);
  EmbreeScene scene(device, RTC_BUILD_QUALITY_HIGH);
  ASSERT_NE(scene.get(), nullptr);
  EXPECT_NO_THROW(scene.commit(device));
}

TEST(Embree, ErrorHookBecomesAnException) {
  EmbreeDevice device;
  rtcNewGeometry(device.get(), static_cast<RTCGeometryType>(99));  // no geometry type has it
  try {
    device.check("creating nonsense");
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("Embree: creating nonsense: "), std::string::npos)
        << e.what();
  }
  EXPECT_NO_THROW(device.check("after"));  // the error was reported once
}

}  // namespace
}  // namespace weft::base
