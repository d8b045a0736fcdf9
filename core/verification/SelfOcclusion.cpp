#include "core/verification/SelfOcclusion.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace scanpick::core {

std::vector<char> selfHidden(const std::vector<Eigen::Vector3f>& points_model,
                             const Eigen::Isometry3f& T_scene_model, double spacing_mm,
                             float margin_mm) {
  std::vector<char> hidden(points_model.size(), 0);
  const float distance_mm = T_scene_model.translation().z();
  if (!(spacing_mm > 0) || !(distance_mm > 0) || points_model.empty())
    return hidden;
  // Cells of the image plane at unit depth: a line of sight's direction (x/z, y/z).
  const float cell = 1.5f * static_cast<float>(spacing_mm) / distance_mm;
  std::vector<Eigen::Vector3f> scene(points_model.size());
  Eigen::Vector2f low = Eigen::Vector2f::Constant(std::numeric_limits<float>::max());
  Eigen::Vector2f high = -low;
  for (std::size_t i = 0; i < points_model.size(); ++i) {
    scene[i] = T_scene_model * points_model[i];
    if (!(scene[i].z() > 0))
      return hidden;
    const Eigen::Vector2f at = scene[i].head<2>() / (scene[i].z() * cell);
    low = low.cwiseMin(at);
    high = high.cwiseMax(at);
  }
  const Eigen::Vector2f span = high - low;
  constexpr float kMaxCells = 4e6f;
  if (!((span.x() + 1.0f) * (span.y() + 1.0f) <= kMaxCells))
    return hidden;
  const auto columns = static_cast<std::size_t>(span.x()) + 1;
  const auto rows = static_cast<std::size_t>(span.y()) + 1;
  const auto cellOf = [&](const Eigen::Vector3f& p) {
    const Eigen::Vector2f at = p.head<2>() / (p.z() * cell) - low;
    const auto u = std::min(columns - 1, static_cast<std::size_t>(at.x()));
    const auto v = std::min(rows - 1, static_cast<std::size_t>(at.y()));
    return v * columns + u;
  };
  std::vector<float> nearest_mm(columns * rows, std::numeric_limits<float>::infinity());
  for (const auto& p : scene) {
    float& depth = nearest_mm[cellOf(p)];
    depth = std::min(depth, p.norm());
  }
  for (std::size_t i = 0; i < scene.size(); ++i)
    hidden[i] = nearest_mm[cellOf(scene[i])] < scene[i].norm() - margin_mm;
  return hidden;
}

} // namespace scanpick::core
