#pragma once
// The thesis's ideal test (§5.1, Figure 5.1): a model of two circles and two lines as point
// clouds, and a scene of copies rotated about x, y and z by kπ/5, translated apart.
#include "core/cloud/PointCloud.h"
#include "core/params/Parameters.h"

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

namespace scanpick::test {

/// The part in its design frame (mm): circles of radius 10 and 15, lines of 40 and 60 mm, in the
/// z = 0 plane, laid out without symmetry; gaps inside the part stay below 16 mm.
inline std::vector<Eigen::Vector3f> idealPartPoints() {
  std::vector<Eigen::Vector3f> pts;
  const auto circle = [&](Eigen::Vector2f c, float r, int n) {
    for (int i = 0; i < n; ++i) {
      const float a = 2.0f * float(M_PI) * float(i) / float(n);
      pts.emplace_back(c.x() + r * std::cos(a), c.y() + r * std::sin(a), 0.0f);
    }
  };
  const auto line = [&](Eigen::Vector2f a, Eigen::Vector2f b, float spacing) {
    const int n = static_cast<int>(std::lround((b - a).norm() / spacing));
    for (int i = 0; i <= n; ++i) {
      const Eigen::Vector2f p = a + (b - a) * (float(i) / float(n));
      pts.emplace_back(p.x(), p.y(), 0.0f);
    }
  };
  circle({0, 0}, 10.0f, 300);
  circle({38, 8}, 15.0f, 450);
  line({-10, -22}, {30, -22}, 0.2f); // 40 mm
  const Eigen::Vector2f dir(std::sin(float(M_PI) / 12), std::cos(float(M_PI) / 12));
  line({-20, -15}, Eigen::Vector2f(-20, -15) + 60.0f * dir, 0.2f); // 60 mm
  return pts;
}

/// Poses of the 12 copies in the scene (camera frame): rotations about x, y, z by kπ/5
/// (k = 1..4), on a 4 x 3 grid 150 mm apart, 700 mm in front of the camera.
inline std::vector<Eigen::Isometry3d> idealCopyPoses() {
  std::vector<Eigen::Isometry3d> poses;
  const Eigen::Vector3d axes[3] = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
                                   Eigen::Vector3d::UnitZ()};
  for (int a = 0; a < 3; ++a)
    for (int k = 1; k <= 4; ++k) {
      Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
      T.linear() = Eigen::AngleAxisd(k * M_PI / 5.0, axes[a]).toRotationMatrix();
      T.translation() = Eigen::Vector3d(-225.0 + 150.0 * (k - 1), -150.0 + 150.0 * a, 700.0);
      poses.push_back(T);
    }
  return poses;
}

/// Points of `part` moved by each pose; each point replaced by a uniform random point within
/// `noise_mm` of it (the thesis's noise model), from `seed`.
inline core::PointCloud idealScene(const std::vector<Eigen::Vector3f>& part,
                                   const std::vector<Eigen::Isometry3d>& poses, double noise_mm,
                                   std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::Vector3f> pts;
  for (const auto& T : poses)
    for (const auto& p : part) {
      Eigen::Vector3d q = T * p.cast<double>();
      if (noise_mm > 0) {
        Eigen::Vector3d d;
        do
          d = {u(rng), u(rng), u(rng)};
        while (d.squaredNorm() > 1.0);
        q += noise_mm * d;
      }
      pts.push_back(q.cast<float>());
    }
  return core::PointCloud::fromPoints(std::move(pts));
}

/// Thesis tables 5.1 / 5.2 (ransac size 40, thresholds 1 mm circles / `line_threshold_mm` lines,
/// Δp = -1: every point is a keypoint, matching length and radius 10 mm, position 2 mm,
/// orientation 0.25 rad). Not in the tables: no floor to remove; the object count links points
/// closer than 25 mm (the part's inner gaps are below 16 mm, copies are 70+ mm apart) and counts
/// clusters of 200+ points; circles above 50 mm radius are not searched; score threshold 0.5.
inline core::RecognitionParams idealParams(double line_threshold_mm) {
  core::RecognitionParams p;
  p.floor.enabled = false;
  p.clustering.enabled = true;
  p.clustering.count_radius_mm = 25.0;
  p.clustering.count_min_points = 200;
  p.keypoints.position_range_mm = -1.0;
  p.features.ransac_size = 40;
  p.features.circle_threshold_mm = 1.0;
  p.features.line_threshold_mm = line_threshold_mm;
  p.features.max_circle_radius_mm = 50.0;
  p.matching.length_tolerance_mm = 10.0;
  p.matching.radius_tolerance_mm = 10.0;
  p.matching.position_tolerance_mm = 2.0;
  p.matching.orientation_tolerance_rad = 0.25;
  p.matching.score_threshold = 0.5;
  return p;
}

} // namespace scanpick::test
