#pragma once
// Writes an .oni recording without hardware: OpenNI 1.x's mock depth generator recorded by its
// recorder (OpenNI2's own DummyDevice + Recorder writes files that play back zero frames).
// The result is played back through OpenNI2 by the code under test.
#include "core/cloud/PointCloud.h"

#include <XnCppWrapper.h>
#include <XnPropNames.h>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace scanpick::test {

/// Records `frames` copies of the depth of `scene_mm` (organized; z rounded to whole mm, 0 where
/// invalid) with the given fields of view (radians). Returns an empty string on success, else
/// the OpenNI error.
inline std::string recordOni(const std::filesystem::path& path, const core::PointCloud& scene_mm,
                             int frames, double hfov_rad, double vfov_rad) {
  const XnUInt32 w = scene_mm.width, h = scene_mm.height;
  std::vector<XnDepthPixel> depth(static_cast<std::size_t>(w) * h, 0);
  for (std::size_t i = 0; i < depth.size(); ++i) {
    const float z = scene_mm.points_mm[i].z();
    depth[i] =
        std::isfinite(z) && z > 0 && z < 65535 ? static_cast<XnDepthPixel>(std::lround(z)) : 0;
  }
  xn::Context context;
  XnStatus s = context.Init();
  auto fail = [&](const char* step) { return std::string(step) + ": " + xnGetStatusString(s); };
  if (s != XN_STATUS_OK)
    return fail("Context::Init");
  xn::MockDepthGenerator mock;
  if ((s = mock.Create(context, "scanpick-mock-depth")) != XN_STATUS_OK)
    return fail("MockDepthGenerator::Create");
  // Without the mirror capability AddNodeToRecording fails with "Function was not implemented".
  mock.SetIntProperty(XN_CAPABILITY_MIRROR, 1);
  mock.SetIntProperty(XN_PROP_MIRROR, 0);
  XnMapOutputMode mode{w, h, 30};
  mock.SetIntProperty(XN_PROP_SUPPORTED_MAP_OUTPUT_MODES_COUNT, 1);
  mock.SetGeneralProperty(XN_PROP_SUPPORTED_MAP_OUTPUT_MODES, sizeof mode, &mode);
  if ((s = mock.SetMapOutputMode(mode)) != XN_STATUS_OK)
    return fail("SetMapOutputMode");
  XnFieldOfView fov{hfov_rad, vfov_rad};
  mock.SetGeneralProperty(XN_PROP_FIELD_OF_VIEW, sizeof fov, &fov);
  XnCropping cropping{};
  cropping.bEnabled = FALSE;
  mock.SetGeneralProperty(XN_PROP_CROPPING, sizeof cropping, &cropping);
  mock.SetIntProperty(XN_PROP_DEVICE_MAX_DEPTH, 10000);
  mock.SetIntProperty(XN_PROP_BYTES_PER_PIXEL, 2);

  xn::Recorder recorder;
  if ((s = recorder.Create(context)) != XN_STATUS_OK)
    return fail("Recorder::Create");
  if ((s = recorder.SetDestination(XN_RECORD_MEDIUM_FILE, path.c_str())) != XN_STATUS_OK)
    return fail("Recorder::SetDestination");
  if ((s = recorder.AddNodeToRecording(mock, XN_CODEC_16Z_EMB_TABLES)) != XN_STATUS_OK)
    return fail("Recorder::AddNodeToRecording");
  for (int f = 0; f < frames; ++f) {
    if ((s = mock.SetData(static_cast<XnUInt32>(f + 1), static_cast<XnUInt64>(f) * 33333,
                          static_cast<XnUInt32>(depth.size() * sizeof(XnDepthPixel)),
                          depth.data())) != XN_STATUS_OK)
      return fail("MockDepthGenerator::SetData");
    if ((s = recorder.Record()) != XN_STATUS_OK)
      return fail("Recorder::Record");
  }
  recorder.Release();
  mock.Release();
  context.Release();
  return {};
}

} // namespace scanpick::test
