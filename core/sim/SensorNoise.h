#pragma once
/// @file SensorNoise.h
/// What makes a simulated scan look like a real one: depth noise, Kinect disparity quantization,
/// dropouts at grazing angles and at random, and flying pixels at depth edges. All random draws
/// come from a counter-based hash of (seed, pixel, stream), so results do not depend on threads.

#include "core/cloud/Sensor.h"

#include <cstdint>

namespace scanpick::core {

/// Noise model of a structured-light sensor. Defaults = no noise at all.
struct SensorNoise {
  double z_sigma_mm = 0;          ///< Gaussian depth noise along the ray, truncated at ±4σ
  double disparity_step_px = 0;   ///< Kinect: disparity quantization step (1/8 px); 0 = none
  double disparity_sigma_px = 0;  ///< Kinect: Gaussian disparity noise before quantization
  double dropout_probability = 0; ///< chance that any point is missing
  /// A point is missing when the camera or the projector sees the surface at an angle whose cosine
  /// is below this (0.1 ≈ 84° from the normal); 0 = off.
  double grazing_cos = 0;
  double flying_probability = 0; ///< chance that a pixel at a depth edge is a mixed pixel
  double flying_edge_mm = 0;     ///< depth jump to a 4-neighbour that makes an edge

  /// The sensor's typical noise: PhoXi M: σ = sensor.noise_sigma_mm (0.1 mm), 0.2 % dropouts,
  /// grazing limit 0.1, a few flying pixels at > 3 mm edges; Kinect v1: 1/8 px disparity steps
  /// (≈ 12 mm at 2 m), 0.05 px disparity noise, 1 % dropouts, many flying pixels at > 15 mm edges.
  static SensorNoise typical(const SensorModel& sensor);
  /// `typical(sensor)` with the Gaussian depth noise replaced by `sigma_mm` (Kinect: the
  /// disparity noise is replaced too; its quantization stays, being part of how depth is measured).
  static SensorNoise withSigma(const SensorModel& sensor, double sigma_mm);
  /// Exact geometry: no noise, no dropouts, no flying pixels (grazing limit off).
  static SensorNoise none() { return {}; }
};

/// 64-bit mix of (seed, counter, stream) (SplitMix64 finalizer rounds): the counter-based random
/// source of the simulator.
std::uint64_t hashMix(std::uint64_t seed, std::uint64_t counter, std::uint64_t stream);
/// Uniform in [0, 1) from hashMix.
double hashUniform(std::uint64_t seed, std::uint64_t counter, std::uint64_t stream);
/// Standard normal from hashMix (Box-Muller on two streams).
double hashGaussian(std::uint64_t seed, std::uint64_t counter, std::uint64_t stream);

/// The measured depth (along the optical axis, mm) for a true depth `z_mm`, for pixel `pixel` of a
/// scan with `seed`: Gaussian noise (truncated at 4σ), then disparity noise and quantization with
/// `fx_px` and `baseline_mm`.
double noisyDepth(double z_mm, const SensorNoise& noise, double fx_px, double baseline_mm,
                  std::uint64_t seed, std::uint64_t pixel);

} // namespace scanpick::core
