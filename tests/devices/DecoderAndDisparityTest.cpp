// Pure conversions: PhoXi multipart buffers -> cloud (on bytes built here) and Kinect raw
// disparity <-> depth.
#include "devices/aravis/MultipartDecoder.h"
#include "devices/freenect/DisparityConversion.h"
#include "tests/devices/SyntheticScene.h"

#include <cmath>
#include <cstring>
#include <gtest/gtest.h>

using namespace scanpick;
using namespace scanpick::devices;

namespace {

template <typename T> std::vector<std::byte> bytesOf(const std::vector<T>& values) {
  std::vector<std::byte> out(values.size() * sizeof(T));
  std::memcpy(out.data(), values.data(), out.size());
  return out;
}

std::vector<float> abc(const core::PointCloud& c) {
  std::vector<float> out;
  for (const auto& p : c.points_mm)
    for (int k = 0; k < 3; ++k)
      out.push_back(core::isValid(p) ? p[k] : 0.0f);
  return out;
}

} // namespace

TEST(MultipartDecoder, DecodesRangeNormalConfidenceAndIntensity) {
  const core::PointCloud scene = test::syntheticBinScene(64, 48);
  const std::size_t n = scene.size();
  std::vector<float> normals(3 * n);
  std::vector<std::uint8_t> confidence(n);
  std::vector<std::uint16_t> intensity(n);
  for (std::size_t i = 0; i < n; ++i) {
    normals[3 * i + 2] = -1.0f;
    normals[3 * i] = static_cast<float>(i % 7) * 0.01f;
    confidence[i] = static_cast<std::uint8_t>(i % 256);
    intensity[i] = static_cast<std::uint16_t>(i * 13 % 4096);
  }
  const auto range_bytes = bytesOf(abc(scene)), normal_bytes = bytesOf(normals),
             conf_bytes = bytesOf(confidence), int_bytes = bytesOf(intensity);
  // Order differs from the component order on purpose: kinds, not positions, decide.
  const std::vector<BufferPart> parts = {
      {PartKind::Intensity, pfnc::kMono12, 64, 48, int_bytes},
      {PartKind::Normal, pfnc::kCoord3dAbc32f, 64, 48, normal_bytes},
      {PartKind::Range, pfnc::kCoord3dAbc32f, 64, 48, range_bytes},
      {PartKind::Confidence, pfnc::kConfidence8, 64, 48, conf_bytes}};
  const core::PointCloud got = decodeParts(parts);
  ASSERT_EQ(got.width, 64u);
  ASSERT_EQ(got.height, 48u);
  ASSERT_EQ(got.normals.size(), n);
  ASSERT_EQ(got.confidence.size(), n);
  ASSERT_EQ(got.intensity.size(), n);
  for (std::size_t i = 0; i < n; ++i) {
    if (core::isValid(scene.points_mm[i]))
      EXPECT_EQ(got.points_mm[i], scene.points_mm[i]);
    else
      EXPECT_FALSE(core::isValid(got.points_mm[i])); // (0,0,0) became NaN
    EXPECT_EQ(got.normals[i],
              Eigen::Vector3f(normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]));
    EXPECT_EQ(got.confidence[i], confidence[i]);
    EXPECT_EQ(got.intensity[i], static_cast<float>(intensity[i]));
  }
}

TEST(MultipartDecoder, ProjectedC32fUsesScan3dParametersAndCoordinateMaps) {
  const std::uint32_t w = 8, h = 6;
  std::vector<float> z(w * h, 700.0f), a(w * h), b(w * h);
  z[5] = 0.0f; // no measurement
  for (std::uint32_t i = 0; i < w * h; ++i) {
    a[i] = static_cast<float>(i % w) + 0.25f; // sub-pixel coordinate maps
    b[i] = static_cast<float>(i / w) - 0.5f;
  }
  const ProjectedCParams p{1000.0, 1.1, 3.5, 2.5};
  const auto zb = bytesOf(z), ab = bytesOf(a), bb = bytesOf(b);
  const std::vector<BufferPart> with_maps = {
      {PartKind::Range, pfnc::kCoord3dC32f, w, h, zb},
      {PartKind::CoordinateMapA, pfnc::kCoord3dA32f, w, h, ab},
      {PartKind::CoordinateMapB, pfnc::kCoord3dB32f, w, h, bb}};
  const core::PointCloud c = decodeParts(with_maps, p);
  EXPECT_FALSE(core::isValid(c.points_mm[5]));
  const std::size_t i = 2 * w + 6;
  // x = z (A - ppu) / f = 700 (6.25 - 3.5) / 1000; y = z (B - ppv) / (f aspect) = 700 (1.5 - 2.5) /
  // 1100
  EXPECT_NEAR(c.points_mm[i].x(), 700.0 * 2.75 / 1000.0, 1e-4);
  EXPECT_NEAR(c.points_mm[i].y(), -700.0 / 1100.0, 1e-4);
  EXPECT_EQ(c.points_mm[i].z(), 700.0f);
  // Without maps, A/B are the column and row.
  const std::vector<BufferPart> plain = {{PartKind::Range, pfnc::kCoord3dC32f, w, h, zb}};
  EXPECT_NEAR(decodeParts(plain, p).points_mm[i].x(), 700.0 * 2.5 / 1000.0, 1e-4);
  EXPECT_THROW(decodeParts(plain), DeviceError); // C32f needs the projection parameters
}

TEST(MultipartDecoder, RejectsMalformedBuffersWithProtocolErrors) {
  const std::vector<float> xyz(3 * 4 * 4, 1.0f);
  const auto bytes = bytesOf(xyz);
  const std::span<const std::byte> half(bytes.data(), bytes.size() / 2);
  auto kindOf = [](const std::vector<BufferPart>& parts) {
    try {
      decodeParts(parts);
    } catch (const DeviceError& e) {
      return e.kind();
    }
    return DeviceErrorKind::Unsupported; // "no error" marker, never expected below
  };
  EXPECT_EQ(kindOf({{PartKind::Intensity, pfnc::kMono8, 4, 4, bytes}}),
            DeviceErrorKind::Protocol); // no Range
  EXPECT_EQ(kindOf({{PartKind::Range, pfnc::kCoord3dAbc32f, 4, 4, half}}),
            DeviceErrorKind::Protocol); // truncated
  EXPECT_EQ(kindOf({{PartKind::Range, pfnc::kCoord3dAbc32f, 4, 4, bytes},
                    {PartKind::Confidence, pfnc::kConfidence8, 2, 2, bytes}}),
            DeviceErrorKind::Protocol); // grids disagree
  EXPECT_EQ(kindOf({{PartKind::Range, 0x01080099u, 4, 4, bytes}}),
            DeviceErrorKind::Protocol); // unknown format
}

TEST(MultipartDecoder, GuessesComponentsFromPixelFormats) {
  EXPECT_EQ(guessPartKind(pfnc::kCoord3dAbc32f, false), PartKind::Range);
  EXPECT_EQ(guessPartKind(pfnc::kCoord3dAbc32f, true), PartKind::Normal);
  EXPECT_EQ(guessPartKind(pfnc::kConfidence8, true), PartKind::Confidence);
  EXPECT_EQ(guessPartKind(pfnc::kMono16, true), PartKind::Intensity);
}

TEST(DisparityConversion, RoundTripStaysWithinHalfAStep) {
  // Over the Kinect's working range every depth survives depth -> raw -> depth within half a
  // disparity step, which grows as z^2.
  double worst_ratio = 0;
  for (float z = 500.0f; z <= 4000.0f; z += 0.7f) {
    const std::uint16_t raw = depthMmToDisparity(z);
    ASSERT_NE(raw, kDisparityNoData) << z;
    const double dz = std::abs(disparityToDepthMm(raw) - z);
    worst_ratio = std::max(worst_ratio, dz / disparityQuantizationMm(z));
  }
  EXPECT_LE(worst_ratio, 1.01);
  EXPECT_GT(worst_ratio, 0.9); // the bound is tight, not loose
  EXPECT_NEAR(disparityQuantizationMm(1000.0), 1.5356, 1e-3);
}

TEST(DisparityConversion, NoDataAndOutOfRange) {
  EXPECT_TRUE(std::isnan(disparityToDepthMm(kDisparityNoData)));
  EXPECT_TRUE(std::isnan(disparityToDepthMm(1090))); // beyond the model's pole (raw ~1084.6)
  EXPECT_EQ(depthMmToDisparity(std::numeric_limits<float>::quiet_NaN()), kDisparityNoData);
  EXPECT_EQ(depthMmToDisparity(100.0f), kDisparityNoData); // closer than raw 0 can express
  EXPECT_NEAR(disparityToDepthMm(0), 1000.0 / kDisparityOffset, 1e-3);
}

TEST(DisparityConversion, CloudUsesTheKinectPinholeModel) {
  const Intrinsics k = kinectDepthIntrinsics();
  EXPECT_EQ(k.width, 640);
  EXPECT_NEAR(k.fx, 320.0 / std::tan(29.0 * 3.14159265358979 / 180.0), 1e-6);
  std::vector<std::uint16_t> raw(640 * 480, kDisparityNoData);
  raw[100 * 640 + 500] = 800;
  const core::PointCloud c = disparityToCloud(raw, k);
  EXPECT_EQ(c.validCount(), 1u);
  const Eigen::Vector3f p = c.points_mm[100 * 640 + 500];
  EXPECT_NEAR(p.x(), (500 - k.cx) * p.z() / k.fx, 1e-3);
  EXPECT_NEAR(p.y(), (100 - k.cy) * p.z() / k.fy, 1e-3);
  EXPECT_THROW(disparityToCloud(std::vector<std::uint16_t>(10), k), DeviceError);
}
