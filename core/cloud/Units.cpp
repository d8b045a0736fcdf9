#include "core/cloud/Units.h"

#include "core/common/Error.h"

#include <cstdio>

namespace scanpick::core {

LengthUnit parseLengthUnit(std::string_view text) {
  if (text == "mm" || text == "millimetres" || text == "millimeters")
    return LengthUnit::Millimetres;
  if (text == "m" || text == "metres" || text == "meters")
    return LengthUnit::Metres;
  throw Error("unknown length unit '" + std::string(text) + "': use 'mm' or 'm'");
}

std::string toString(LengthUnit unit) {
  return unit == LengthUnit::Metres ? "m" : "mm";
}

float millimetresPer(LengthUnit unit) {
  return unit == LengthUnit::Metres ? 1000.0f : 1.0f;
}

std::optional<LengthUnit> guessLengthUnit(const PointCloud& cloud) {
  const auto box = boundingBox(cloud);
  if (box.isEmpty())
    return std::nullopt;
  return box.diagonal().norm() < 5.0f ? LengthUnit::Metres : LengthUnit::Millimetres;
}

std::string unitsSanityWarning(const PointCloud& cloud, LengthUnit declared) {
  const auto guess = guessLengthUnit(cloud);
  if (!guess || *guess == declared)
    return {};
  const float extent = boundingBox(cloud).diagonal().norm() * millimetresPer(declared);
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "the cloud is read as '%s' but then spans %.4g mm, which is implausible for a "
                "scan: is it in '%s'? pass --units %s",
                toString(declared).c_str(), extent, toString(*guess).c_str(),
                toString(*guess).c_str());
  return buf;
}

} // namespace scanpick::core
