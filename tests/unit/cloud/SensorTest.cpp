#include "core/cloud/Sensor.h"

#include <gtest/gtest.h>
#include <limits>

using namespace scanpick::core;

TEST(SensorModel, PixelOfAPointIsItsProjectionRoundedHalfAwayAndClampedFarOutside) {
  const SensorModel sensor = sensorPreset("phoxi-m-1032");
  // A point on the optical axis lands on the principal point's pixel.
  const auto centre = sensor.pixelOf({0.0f, 0.0f, 800.0f});
  ASSERT_TRUE(centre);
  EXPECT_EQ(centre->x(), int(roundHalfAway(sensor.cx)));
  EXPECT_EQ(centre->y(), int(roundHalfAway(sensor.cy)));
  EXPECT_TRUE(sensor.inImage(*centre));
  // Half a pixel to the right of a pixel centre rounds away from zero.
  const float z = 800.0f;
  const double u = 100.5, v = 40.0;
  const Eigen::Vector3f half(float((u - sensor.cx) * z / sensor.fx),
                             float((v - sensor.cy) * z / sensor.fy), z);
  const Eigen::Vector2d uv = sensor.project(half.cast<double>());
  const auto pixel = sensor.pixelOf(half);
  ASSERT_TRUE(pixel);
  EXPECT_EQ(pixel->x(), int(roundHalfAway(uv.x())));
  EXPECT_EQ(pixel->y(), int(roundHalfAway(uv.y())));
  // Near the camera's plane the projection is clamped, never overflowing, and lies outside.
  const auto far_out = sensor.pixelOf({1000.0f, -1000.0f, 1e-20f});
  ASSERT_TRUE(far_out);
  EXPECT_EQ(far_out->x(), 1000000);
  EXPECT_EQ(far_out->y(), -1000000);
  EXPECT_FALSE(sensor.inImage(*far_out));
  // Behind the camera, on its plane, or not a number: no pixel.
  EXPECT_FALSE(sensor.pixelOf({0.0f, 0.0f, -5.0f}));
  EXPECT_FALSE(sensor.pixelOf({1.0f, 1.0f, 0.0f}));
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_FALSE(sensor.pixelOf({nan, 0.0f, 800.0f}));
  EXPECT_FALSE(sensor.pixelOf({0.0f, 0.0f, nan}));
  // The image's last column and row are in it, one more is not.
  EXPECT_TRUE(sensor.inImage({sensor.width - 1, sensor.height - 1}));
  EXPECT_FALSE(sensor.inImage({sensor.width, 0}));
  EXPECT_FALSE(sensor.inImage({0, sensor.height}));
  EXPECT_FALSE(sensor.inImage({-1, 0}));
  // Row-major: the first pixel, the next row's first, the last.
  EXPECT_EQ(sensor.pixelIndex({0, 0}), 0u);
  EXPECT_EQ(sensor.pixelIndex({0, 1}), std::size_t(sensor.width));
  EXPECT_EQ(sensor.pixelIndex({sensor.width - 1, sensor.height - 1}),
            std::size_t(sensor.width) * std::size_t(sensor.height) - 1);
}
