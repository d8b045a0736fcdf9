#include "core/sim/PartDeformation.h"

#include "core/common/Error.h"
#include "core/sim/SensorNoise.h"

#include <string>

namespace scanpick::core {

Part deformedPart(const Part& part, double fraction, std::uint64_t seed) {
  if (!(fraction >= 0.0 && fraction <= kMaxDeformation))
    throw Error("the deformation must be between 0 and 0.3 (a fraction of the part's size), got " +
                std::to_string(fraction));
  if (fraction == 0.0)
    return part;
  std::uint64_t draw = 0;
  const auto symmetric = [&](double scale) {
    return scale * (2.0 * hashUniform(seed, draw++, 0) - 1.0);
  };
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      A(r, c) += symmetric(r == c ? fraction : 0.5 * fraction);

  // The bend: along the longest axis of the bounding box, across the shortest.
  const Eigen::AlignedBox3d box = boundingBox(part.mesh());
  const Eigen::Vector3d centre = box.center();
  const Eigen::Vector3d extent = box.sizes();
  Eigen::Index along = 0, across = 0;
  extent.maxCoeff(&along);
  extent.minCoeff(&across);
  const double half_length = 0.5 * extent(along);
  // offset = κ (x² − h²/3) across, κ = bend / h: the ends (x = ±h) move by bend · h relative to
  // the middle, and the offset averages to zero along the part.
  const double curvature = half_length > 0 ? symmetric(fraction) / half_length : 0.0;

  Part out = part;
  for (auto& component : out.components)
    for (auto& v : component.vertices_mm) {
      Eigen::Vector3d d = v - centre;
      d(across) += curvature * (d(along) * d(along) - half_length * half_length / 3.0);
      v = centre + A * d;
    }
  return out;
}

} // namespace scanpick::core
