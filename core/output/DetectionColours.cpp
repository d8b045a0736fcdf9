#include "core/output/DetectionColours.h"

#include <array>
#include <cmath>

namespace scanpick::core {

Rgb8 detectionColour(std::size_t index) {
  const double hue = std::fmod(0.08 + double(index) * 0.618033988749895, 1.0);
  constexpr double kSaturation = 0.85, kValue = 1.0;
  // HSV to RGB: the hue's sextant picks which channel rises or falls.
  const double h = hue * 6.0;
  const int sextant = int(std::floor(h)) % 6;
  const double f = h - std::floor(h);
  const double p = kValue * (1.0 - kSaturation);
  const double q = kValue * (1.0 - kSaturation * f);
  const double t = kValue * (1.0 - kSaturation * (1.0 - f));
  const std::array<std::array<double, 3>, 6> rgb = {{{kValue, t, p},
                                                     {q, kValue, p},
                                                     {p, kValue, t},
                                                     {p, q, kValue},
                                                     {t, p, kValue},
                                                     {kValue, p, q}}};
  const auto& c = rgb[std::size_t(sextant)];
  const auto byte = [](double v) { return static_cast<std::uint8_t>(std::lround(255.0 * v)); };
  return {byte(c[0]), byte(c[1]), byte(c[2])};
}

std::vector<Rgb8> detectionColours(std::size_t count) {
  std::vector<Rgb8> colours;
  colours.reserve(count);
  for (std::size_t i = 0; i < count; ++i)
    colours.push_back(detectionColour(i));
  return colours;
}

} // namespace scanpick::core
