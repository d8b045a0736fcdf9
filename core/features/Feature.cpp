#include "core/features/Feature.h"

namespace scanpick::core {

std::string toString(FeatureType type) {
  switch (type) {
  case FeatureType::Line:
    return "line";
  case FeatureType::Circle:
    return "circle";
  }
  return "unknown";
}

} // namespace scanpick::core
