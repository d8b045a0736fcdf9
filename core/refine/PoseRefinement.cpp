#include "core/refine/PoseRefinement.h"

#include "core/common/Error.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace scanpick::core {

namespace {

/// Pairs whose normals differ by more than ~26° are different surfaces (the other side of a thin
/// wall, the floor under a tilted face) or straddle an edge, where PCA normals blend two faces and
/// bias point-to-plane. On the benchmark's 12 brackets (before the edge filter below): 60° gave
/// 0.048 mm mean / 0.12 mm worst error, 26° gave 0.027 / 0.06 mm.
constexpr float kMinNormalCosine = 0.9f;
/// Coarse iterations use every kCoarseStride-th model point: while the pose is still far off,
/// more points would only refine a wrong linearisation.
constexpr std::size_t kCoarseStride = 4;
constexpr std::size_t kMinCoarsePoints = 200;

void checkParams(const RefineParams& params) {
  if (params.max_iterations < 1 || !(params.max_correspondence_mm > 0) ||
      !(params.min_correspondence_mm > 0) || !(params.inlier_distance_mm > 0) ||
      !(params.convergence_mm > 0) || params.model_points < 3 ||
      !(params.min_inlier_fraction >= 0 && params.min_inlier_fraction <= 1))
    throw Error("Refinement parameters out of range: iterations and model points must be "
                "positive, the distances and convergence > 0 mm, and the minimum inlier share in "
                "[0, 1] (see docs/parameters.md, section Refinement).");
}

/// One model point's pair with the scene at the current pose.
struct Pair {
  bool valid = false;
  Eigen::Vector3d p = Eigen::Vector3d::Zero(); ///< model point in the scene frame
  Eigen::Vector3d q = Eigen::Vector3d::Zero(); ///< nearest scene point
  Eigen::Vector3d n = Eigen::Vector3d::Zero(); ///< scene normal at q
  /// Where the point was when the scene was last searched (NaN: never) and what was found there
  /// (-1: nothing within the bound).
  Eigen::Vector3f searched_at = invalidPoint();
  std::int64_t scene_index = -1;
};

/// True when the camera at `viewpoint` sees the front of a surface at `p` with normal `n`.
bool facesViewpoint(const Eigen::Vector3f& p, const Eigen::Vector3f& n,
                    const Eigen::Vector3f& viewpoint) {
  return n.dot(viewpoint - p) > 0.0f;
}

/// The squared distance (mm²) within which the nearest scene point to `p` is looked for: at most
/// `max_distance_sq`, and no farther than the point found for it last time (`last`, -1 for none),
/// with a little to spare (the window of a smaller ball is smaller). Every point as near as the
/// nearest lies within it, so the search answers as within `max_distance_sq`.
float searchBound(const SceneIndex& scene, const Eigen::Vector3f& p, std::int64_t last,
                  float max_distance_sq) {
  if (last < 0)
    return max_distance_sq;
  const float last_sq = (p - scene.points()[static_cast<std::size_t>(last)]).squaredNorm();
  return std::min(max_distance_sq, 1.001f * last_sq + 1e-6f);
}

/// Pairs every stride-th model point with its nearest scene point within sqrt(max_distance_sq).
/// A point that moved less than `reuse_within_mm` since its last search keeps that search's
/// answer (another sample of the same surface at most that much closer changes nothing for
/// point-to-plane); pass 0 to search every point. `pairs` must come from a call with the same
/// stride, or be empty. Each slot is written by one task only, so the result is independent of
/// scheduling.
void findPairs(const RefineModel& model, const SceneIndex& scene, const Eigen::Isometry3d& T,
               std::size_t stride, float max_distance_sq, bool need_normals, float reuse_within_mm,
               std::vector<Pair>& pairs) {
  const Eigen::Matrix3f R = T.linear().cast<float>();
  const Eigen::Vector3f t = T.translation().cast<float>();
  const Eigen::Vector3f viewpoint = scene.options().viewpoint_mm.cast<float>();
  const std::size_t count = (model.size() + stride - 1) / stride;
  if (pairs.size() != count || !(reuse_within_mm > 0))
    pairs.assign(count, Pair{});
  const float reuse_sq = reuse_within_mm * reuse_within_mm;
  // Scene points whose neighbourhood is far less flat than usual straddle an edge: their blended
  // normal would bias point-to-plane (on the benchmark's 5 mm plates: worst error 0.06 mm with
  // them, 0.04 mm without). Relative to the scene's own flatness, so noisier sensors keep theirs.
  const float max_variation = std::clamp(4.0f * scene.typicalVariation(), 0.02f, 0.2f);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 128),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t k = range.begin(); k < range.end(); ++k) {
                        const std::size_t i = k * stride;
                        Pair& pair = pairs[k];
                        pair.valid = false;
                        const Eigen::Vector3f p = R * model.points()[i] + t;
                        const Eigen::Vector3f n_model = R * model.normals()[i];
                        if (!facesViewpoint(p, n_model, viewpoint))
                          continue;
                        // (NaN compares false: a point never searched is searched now.)
                        if (!((p - pair.searched_at).squaredNorm() < reuse_sq)) {
                          pair.searched_at = p;
                          pair.scene_index = scene.nearest(
                              p, searchBound(scene, p, pair.scene_index, max_distance_sq));
                        }
                        const std::int64_t j = pair.scene_index;
                        if (j < 0)
                          continue;
                        const Eigen::Vector3f& q = scene.points()[static_cast<std::size_t>(j)];
                        if ((q - p).squaredNorm() > max_distance_sq)
                          continue;
                        const Eigen::Vector3f& n_scene =
                            scene.normals()[static_cast<std::size_t>(j)];
                        if (need_normals &&
                            (!n_scene.allFinite() || n_scene.dot(n_model) < kMinNormalCosine ||
                             scene.surfaceVariation()[static_cast<std::size_t>(j)] > max_variation))
                          continue;
                        pair.valid = true;
                        pair.p = p.cast<double>();
                        pair.q = q.cast<double>();
                        pair.n = n_scene.allFinite() ? Eigen::Vector3d(n_scene.cast<double>())
                                                     : Eigen::Vector3d::Zero();
                      }
                    });
}

/// Exponential of a small twist (rotation vector omega, translation): the rigid increment.
Eigen::Isometry3d increment(const Eigen::Matrix<double, 6, 1>& x) {
  Eigen::Isometry3d dT = Eigen::Isometry3d::Identity();
  const Eigen::Vector3d omega = x.head<3>();
  const double angle = omega.norm();
  if (angle > 0)
    dT.linear() = Eigen::AngleAxisd(angle, omega / angle).toRotationMatrix();
  dT.translation() = x.tail<3>();
  return dT;
}

/// The turn about `pivot` (scene frame, mm) by the twist `x`, applied to the pose `T`.
Eigen::Isometry3d turnedAbout(const Eigen::Isometry3d& T, const Eigen::Matrix<double, 6, 1>& x,
                              const Eigen::Vector3d& pivot) {
  Eigen::Isometry3d dT = increment(x);
  dT.translation() += pivot - dT.linear() * pivot;
  return dT * T;
}

/// The Gauss-Newton system of one iteration: J^T W J and J^T W r over the used pairs.
struct LinearSystem {
  Eigen::Matrix<double, 6, 6> A = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> b = Eigen::Matrix<double, 6, 1>::Zero();
  double sum_sq_distance = 0; ///< of the used pairs (mm²)
  std::size_t used = 0;       ///< pairs with a positive weight
  /// Mean of the valid pairs' model points (scene frame, mm): point-to-plane turns about it.
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
};

/// Gauss-Newton on the linearised error of the valid `pairs`, summed in point order (bitwise
/// reproducible). Tukey weights with the current pair distance `distance_mm` as scale fade out
/// pairs near the cut-off. Point-to-plane turns about the pairs' centroid, its rotation scaled
/// by `radius_mm`, so that the six unknowns are comparable and the weak ones can be told.
LinearSystem linearise(const std::vector<Pair>& pairs, bool point_to_plane, double distance_mm,
                       double radius_mm) {
  LinearSystem system;
  Eigen::Matrix<double, 6, 6>& A = system.A;
  Eigen::Matrix<double, 6, 1>& b = system.b;
  Eigen::Vector3d& centroid = system.centroid;
  std::size_t valid = 0;
  for (const Pair& pair : pairs)
    if (pair.valid) {
      centroid += pair.p;
      ++valid;
    }
  if (valid > 0)
    centroid /= static_cast<double>(valid);
  for (const Pair& pair : pairs) {
    if (!pair.valid)
      continue;
    const Eigen::Vector3d d = pair.p - pair.q;
    const double distance_sq = d.squaredNorm();
    const double residual = point_to_plane ? pair.n.dot(d) : std::sqrt(distance_sq);
    const double u = residual / distance_mm;
    const double w = std::max(0.0, 1.0 - u * u);
    if (w <= 0)
      continue;
    const double weight = w * w;
    if (point_to_plane) {
      Eigen::Matrix<double, 6, 1> J;
      J << (pair.p - centroid).cross(pair.n) / radius_mm, pair.n;
      A.noalias() += weight * J * J.transpose();
      b.noalias() += weight * J * pair.n.dot(d);
    } else {
      // d(p') = -[p']x omega + t for a small rotation omega about the scene origin.
      Eigen::Matrix<double, 3, 6> J;
      J << -(Eigen::Matrix3d() << 0, -pair.p.z(), pair.p.y(), pair.p.z(), 0, -pair.p.x(),
             -pair.p.y(), pair.p.x(), 0)
                .finished(),
          Eigen::Matrix3d::Identity();
      A.noalias() += weight * J.transpose() * J;
      b.noalias() += weight * J.transpose() * d;
    }
    system.sum_sq_distance += distance_sq;
    ++system.used;
  }
  return system;
}

/// The increment that solves `system`: rotation omega and the translation at the origin
/// (point-to-point) or at the centroid (point-to-plane). Point-to-point adds a tiny ridge to A.
Eigen::Matrix<double, 6, 1> solveIncrement(LinearSystem& system, bool point_to_plane,
                                           double stable_share, double radius_mm) {
  Eigen::Matrix<double, 6, 6>& A = system.A;
  const Eigen::Matrix<double, 6, 1>& b = system.b;
  Eigen::Matrix<double, 6, 1> x;
  if (point_to_plane) {
    // Only the directions the surface pins down move (Gelfand et al., "Geometrically stable
    // sampling for the ICP algorithm", 2003): a plate seen face-on constrains its tilt and
    // depth but hardly its slide and turn within its plane, where point-to-plane ICP would
    // drift on sensor noise, and a pipe does not constrain its turn about its axis. Directions
    // weaker than stable_share of the strongest keep the pose they came with.
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eigen(A);
    const double strongest = eigen.eigenvalues()(5);
    x.setZero();
    for (int k = 0; k < 6; ++k)
      if (eigen.eigenvalues()(k) > stable_share * strongest)
        x += eigen.eigenvectors().col(k) *
             (eigen.eigenvectors().col(k).dot(-b) / eigen.eigenvalues()(k));
    x.head<3>() /= radius_mm;
  } else {
    // A tiny ridge keeps flat or symmetric models (rank-deficient A) from exploding along the
    // unconstrained directions; it does not bias constrained ones measurably.
    A.diagonal().array() += 1e-9 * A.trace() / 6.0;
    x = A.ldlt().solve(-b);
  }
  return x;
}

/// Final check on all points at pose `T`: sets the result's pose, its visible model points, the
/// share of them with a scene point within params.inlier_distance_mm, and their residual.
void scorePose(const RefineModel& model, const SceneIndex& scene, const Eigen::Isometry3d& T,
               const RefineParams& params, RefinementResult& result) {
  std::vector<Pair> pairs;
  findPairs(model, scene, T, 1,
            static_cast<float>(params.inlier_distance_mm * params.inlier_distance_mm), false, 0.0f,
            pairs);
  const Eigen::Vector3f viewpoint = scene.options().viewpoint_mm.cast<float>();
  const Eigen::Matrix3f R = T.linear().cast<float>();
  const Eigen::Vector3f t = T.translation().cast<float>();
  std::size_t visible = 0, inliers = 0;
  double sum_sq = 0;
  for (std::size_t i = 0; i < model.size(); ++i) {
    if (facesViewpoint(R * model.points()[i] + t, R * model.normals()[i], viewpoint))
      ++visible;
    const Pair& pair = pairs[i];
    if (!pair.valid)
      continue;
    ++inliers;
    const Eigen::Vector3d d = pair.p - pair.q;
    const double r =
        params.point_to_plane && pair.n != Eigen::Vector3d::Zero() ? pair.n.dot(d) : d.norm();
    sum_sq += r * r;
  }
  result.T_scene_model = T;
  result.visible_points = visible;
  result.inlier_fraction =
      visible ? static_cast<double>(inliers) / static_cast<double>(visible) : 0;
  result.rmse_mm = inliers ? std::sqrt(sum_sq / static_cast<double>(inliers)) : 0;
}

} // namespace

RefinementResult refinePose(const RefineModel& model, const SceneIndex& scene,
                            const Eigen::Isometry3d& T_scene_model_initial,
                            const RefineParams& params, const ProgressFn& progress,
                            double stable_share) {
  checkParams(params);
  if (!(stable_share >= 0.0 && stable_share < 1.0))
    throw Error("ICP's share of the strongest curvature below which it holds a direction must lie "
                "in [0, 1).");
  if (model.size() == 0 || scene.size() == 0)
    throw Error("Refinement needs model and scene points: both are empty.");
  RefinementResult result;
  Eigen::Isometry3d T = T_scene_model_initial;
  const double floor_mm = std::min(params.min_correspondence_mm, params.max_correspondence_mm);
  double distance_mm = params.max_correspondence_mm;
  // Coarse iterations (every kCoarseStride-th point) until the steps are small (the pair distance
  // shrinks meanwhile), then all points until the steps fall below convergence_mm: most of the
  // nearest-neighbour queries happen while few points are in play.
  bool fine = model.size() < kCoarseStride * kMinCoarsePoints;
  bool settled = false;
  int small_steps = 0;
  std::vector<Pair> pairs;

  for (int iteration = 0; iteration < params.max_iterations; ++iteration) {
    reportProgress(progress, static_cast<double>(iteration) / params.max_iterations);
    const std::size_t stride = fine ? 1 : kCoarseStride;
    // Search again only points that moved more than 5 % of the final pair distance (in coarse
    // iterations everything moves more than that). Point-to-point needs the exact nearest.
    findPairs(model, scene, T, stride, static_cast<float>(distance_mm * distance_mm),
              params.point_to_plane,
              params.point_to_plane ? static_cast<float>(0.05 * floor_mm) : 0.0f, pairs);
    const double radius_mm = std::max(1.0, model.radius_mm());
    LinearSystem system = linearise(pairs, params.point_to_plane, distance_mm, radius_mm);
    if (system.used < 6)
      break; // too few pairs to fix six degrees of freedom: keep the last pose
    result.iterations = iteration + 1;
    const Eigen::Matrix<double, 6, 1> x =
        solveIncrement(system, params.point_to_plane, stable_share, radius_mm);
    if (!x.allFinite())
      break;
    const Eigen::Vector3d& centroid = system.centroid;
    const Eigen::Vector3d pivot = params.point_to_plane ? centroid : Eigen::Vector3d::Zero();
    T = turnedAbout(T, x, pivot);

    const double motion_mm = (x.head<3>().cross(centroid - pivot) + x.tail<3>()).norm() +
                             x.head<3>().norm() * model.radius_mm();
    const double rms_mm = std::sqrt(system.sum_sq_distance / static_cast<double>(system.used));
    distance_mm = std::clamp(3.0 * rms_mm, floor_mm, distance_mm);
    if (!fine) {
      fine = motion_mm < 10 * params.convergence_mm;
      continue;
    }
    // Pairs can flip between neighbouring scene samples and make the pose cycle with steps just
    // above convergence_mm; three small steps in a row count as settled too.
    small_steps = motion_mm < 2 * params.convergence_mm ? small_steps + 1 : 0;
    if (motion_mm < params.convergence_mm || small_steps >= 3) {
      settled = true;
      break;
    }
  }

  scorePose(model, scene, T, params, result);
  result.converged = settled && result.inlier_fraction >= params.min_inlier_fraction;
  reportProgress(progress, 1.0);
  return result;
}

RefinementResult refinePose(const PointCloud& model_mm, const SceneIndex& scene,
                            const Eigen::Isometry3d& T_scene_model_initial,
                            const RefineParams& params, const ProgressFn& progress) {
  checkParams(params);
  const RefineModel model(model_mm, params.model_points);
  return refinePose(model, scene, T_scene_model_initial, params, progress);
}

RefinementResult refinePose(const PointCloud& model_mm, const PointCloud& scene_mm,
                            const Eigen::Isometry3d& T_scene_model_initial,
                            const RefineParams& params, const ProgressFn& progress) {
  checkParams(params);
  const RefineModel model(model_mm, params.model_points);
  const SceneIndex scene(scene_mm, {}, subProgress(progress, 0.0, 0.5));
  return refinePose(model, scene, T_scene_model_initial, params, subProgress(progress, 0.5, 1.0));
}

double coverageScore(const RefineModel& model, const SceneIndex& scene,
                     const Eigen::Isometry3d& T_scene_model, double tolerance_mm) {
  if (!(tolerance_mm > 0))
    throw Error("The coverage tolerance must be > 0 mm (got " + std::to_string(tolerance_mm) +
                ").");
  std::vector<Pair> pairs;
  findPairs(model, scene, T_scene_model, 1, static_cast<float>(tolerance_mm * tolerance_mm), false,
            0.0f, pairs);
  const Eigen::Vector3f viewpoint = scene.options().viewpoint_mm.cast<float>();
  const Eigen::Matrix3f R = T_scene_model.linear().cast<float>();
  const Eigen::Vector3f t = T_scene_model.translation().cast<float>();
  std::size_t visible = 0, confirmed = 0;
  for (std::size_t i = 0; i < model.size(); ++i) {
    visible += facesViewpoint(R * model.points()[i] + t, R * model.normals()[i], viewpoint) ? 1 : 0;
    confirmed += pairs[i].valid ? 1 : 0;
  }
  return visible ? static_cast<double>(confirmed) / static_cast<double>(visible) : 0.0;
}

} // namespace scanpick::core
