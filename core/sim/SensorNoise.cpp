#include "core/sim/SensorNoise.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace scanpick::core {

SensorNoise SensorNoise::typical(const SensorModel& sensor) {
  SensorNoise n;
  n.grazing_cos = 0.1;
  if (sensor.preset == "kinect-v1") {
    n.disparity_step_px = 1.0 / 8.0;
    n.disparity_sigma_px = 0.05;
    n.dropout_probability = 0.01;
    n.flying_probability = 0.5;
    n.flying_edge_mm = 15.0;
  } else {
    n.z_sigma_mm = sensor.noise_sigma_mm > 0 ? sensor.noise_sigma_mm : 0.1;
    n.dropout_probability = 0.002;
    n.flying_probability = 0.1;
    n.flying_edge_mm = 3.0;
  }
  return n;
}

SensorNoise SensorNoise::withSigma(const SensorModel& sensor, double sigma_mm) {
  SensorNoise n = typical(sensor);
  n.z_sigma_mm = std::max(0.0, sigma_mm);
  n.disparity_sigma_px = 0;
  return n;
}

std::uint64_t hashMix(std::uint64_t seed, std::uint64_t counter, std::uint64_t stream) {
  auto mix = [](std::uint64_t z) {
    z += 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  };
  return mix(mix(mix(seed) ^ counter) ^ (stream * 0xD6E8FEB86659FD93ull));
}

double hashUniform(std::uint64_t seed, std::uint64_t counter, std::uint64_t stream) {
  return static_cast<double>(hashMix(seed, counter, stream) >> 11) * 0x1.0p-53;
}

double hashGaussian(std::uint64_t seed, std::uint64_t counter, std::uint64_t stream) {
  const double u1 = 1.0 - hashUniform(seed, counter, 2 * stream); // (0, 1]
  const double u2 = hashUniform(seed, counter, 2 * stream + 1);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

double noisyDepth(double z_mm, const SensorNoise& noise, double fx_px, double baseline_mm,
                  std::uint64_t seed, std::uint64_t pixel) {
  double z = z_mm;
  if (noise.z_sigma_mm > 0)
    z += noise.z_sigma_mm * std::clamp(hashGaussian(seed, pixel, 1), -4.0, 4.0);
  if ((noise.disparity_step_px > 0 || noise.disparity_sigma_px > 0) && baseline_mm > 0 && z > 0) {
    // Triangulation measures disparity d = f b / z; its noise and steps are uniform in d, so
    // depth errors grow with z².
    double d = fx_px * baseline_mm / z;
    if (noise.disparity_sigma_px > 0)
      d += noise.disparity_sigma_px * std::clamp(hashGaussian(seed, pixel, 2), -4.0, 4.0);
    if (noise.disparity_step_px > 0)
      d = std::max(noise.disparity_step_px,
                   std::round(d / noise.disparity_step_px) * noise.disparity_step_px);
    z = fx_px * baseline_mm / d;
  }
  return z;
}

} // namespace scanpick::core
