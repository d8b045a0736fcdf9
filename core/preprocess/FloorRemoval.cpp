#include "core/preprocess/FloorRemoval.h"

#include "core/common/Error.h"

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/sample_consensus/ransac.h>
#include <pcl/sample_consensus/sac_model_plane.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace scanpick::core {
namespace {

/// PCL seeds its sampler with a constant; this exposes the generator so our seed drives it.
class SeededPlaneModel : public pcl::SampleConsensusModelPlane<pcl::PointXYZ> {
public:
  using pcl::SampleConsensusModelPlane<pcl::PointXYZ>::SampleConsensusModelPlane;
  void seed(std::uint64_t s) { rng_alg_.seed(static_cast<unsigned>(s ^ (s >> 32))); }
};

/// RANSAC on a sample is as good as on all points for a dominant plane and 10-20x cheaper.
constexpr std::size_t kMaxSamplePoints = 60000;
constexpr int kPlaneTrials = 500;

} // namespace

FloorRemovalResult removeFloor(const PointCloud& scene_mm, const FloorParams& params,
                               std::uint64_t seed, const ProgressFn& progress) {
  scene_mm.validate();
  if (params.distance_mm <= 0)
    throw Error("floor removal needs a positive plane distance (floor.distance_mm), got " +
                std::to_string(params.distance_mm));
  FloorRemovalResult result;
  std::vector<char> removed(scene_mm.size(), 0);
  std::vector<int> alive;
  alive.reserve(scene_mm.size());
  for (std::size_t i = 0; i < scene_mm.size(); ++i)
    if (isValid(scene_mm.points_mm[i]))
      alive.push_back(static_cast<int>(i));
  const std::size_t total_valid = alive.size();

  const int planes = params.enabled ? params.max_planes : 0;
  for (int plane = 0; plane < planes && alive.size() >= 3; ++plane) {
    reportProgress(progress, static_cast<double>(plane) / planes);
    // Evenly strided sample of the remaining points: deterministic and spatially uniform.
    const std::size_t stride = std::max<std::size_t>(1, alive.size() / kMaxSamplePoints);
    auto sample = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
    for (std::size_t j = 0; j < alive.size(); j += stride) {
      const auto& p = scene_mm.points_mm[static_cast<std::size_t>(alive[j])];
      sample->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
    }
    auto model = std::make_shared<SeededPlaneModel>(sample);
    model->seed(seed + 0x9e3779b97f4a7c15ULL * static_cast<std::uint64_t>(plane + 1));
    pcl::RandomSampleConsensus<pcl::PointXYZ> ransac(model, params.distance_mm);
    ransac.setMaxIterations(kPlaneTrials);
    if (!ransac.computeModel())
      break;
    pcl::Indices inliers;
    ransac.getInliers(inliers);
    Eigen::VectorXf coefficients;
    ransac.getModelCoefficients(coefficients);
    if (inliers.size() >= 3) {
      Eigen::VectorXf refined;
      model->optimizeModelCoefficients(inliers, coefficients, refined);
      if (refined.size() == 4 && refined.allFinite())
        coefficients = refined;
    }
    Eigen::Vector4f plane_coefficients = coefficients.head<4>();
    plane_coefficients /= plane_coefficients.head<3>().norm();
    if (plane_coefficients[3] < 0)  // the camera (origin) on the positive side
      plane_coefficients = -plane_coefficients;

    // Classify every remaining point against the refined plane.
    std::vector<char> on_plane(alive.size(), 0);
    const float distance = static_cast<float>(params.distance_mm);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, alive.size(), 16384),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t j = r.begin(); j < r.end(); ++j) {
                          const auto& p = scene_mm.points_mm[static_cast<std::size_t>(alive[j])];
                          on_plane[j] = std::abs(plane_coefficients.head<3>().dot(p) +
                                                 plane_coefficients[3]) <= distance;
                        }
                      });
    const auto count = static_cast<std::size_t>(std::count(on_plane.begin(), on_plane.end(), 1));
    if (static_cast<double>(count) < params.min_plane_fraction * static_cast<double>(total_valid) ||
        count == 0)
      break;  // the largest remaining plane is too small: no more floor or walls
    std::vector<int> still_alive;
    still_alive.reserve(alive.size() - count);
    for (std::size_t j = 0; j < alive.size(); ++j) {
      if (on_plane[j])
        removed[static_cast<std::size_t>(alive[j])] = 1;
      else
        still_alive.push_back(alive[j]);
    }
    alive.swap(still_alive);
    result.planes.push_back(plane_coefficients);
    result.removed_points += count;
  }

  if (scene_mm.isOrganized()) {
    result.remaining = scene_mm;
    for (std::size_t i = 0; i < removed.size(); ++i)
      if (removed[i])
        result.remaining.points_mm[i] = invalidPoint();
  } else {
    PointCloud marked = scene_mm;
    for (std::size_t i = 0; i < removed.size(); ++i)
      if (removed[i])
        marked.points_mm[i] = invalidPoint();
    result.remaining = dropInvalid(marked);
  }
  reportProgress(progress, 1.0);
  return result;
}

} // namespace scanpick::core
