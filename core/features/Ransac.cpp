#include "core/features/Ransac.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace scanpick::core {

bool ransacModel(pcl::SampleConsensusModel<pcl::PointXYZ>& model, double threshold_mm,
                 int max_iterations, Eigen::VectorXf& best) {
  constexpr double kProbability = 0.99;
  constexpr double kEpsilon = std::numeric_limits<double>::epsilon();
  const double log_probability = std::log(1.0 - kProbability);
  const double one_over_indices = 1.0 / static_cast<double>(model.getIndices()->size());
  const auto max_skip = static_cast<unsigned>(max_iterations) * 10;
  unsigned skipped = 0;
  int iterations = 0;
  std::size_t best_count = 0;
  double k = std::numeric_limits<double>::max(); // trials needed at the best inlier ratio
  pcl::Indices selection;
  Eigen::VectorXf c(model.getModelSize());
  while (true) {
    model.getSamples(iterations, selection);
    if (selection.empty())
      break;
    if (!model.computeModelCoefficients(selection, c)) {
      if (++skipped < max_skip)
        continue;
      break;
    }
    const std::size_t count = model.countWithinDistance(c, threshold_mm);
    if (count > best_count) {
      best_count = count;
      best = c;
      const double w = static_cast<double>(count) * one_over_indices;
      const double p_outliers = std::clamp(1.0 - std::pow(w, static_cast<double>(selection.size())),
                                           kEpsilon, 1.0 - kEpsilon);
      k = log_probability / std::log(p_outliers);
    }
    ++iterations;
    if (iterations > k || iterations > max_iterations)
      break;
  }
  return best_count > 0;
}

} // namespace scanpick::core
