#pragma once
/// @file RefineModel.h
/// The taught model prepared for refinement: a deterministic, spatially even subsample of its
/// points with unit normals facing the teach camera. Built once per model.

#include "core/cloud/PointCloud.h"
#include "core/refine/SceneIndex.h"

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <vector>

namespace scanpick::core {

/// Model points (model frame, mm) and normals used by refinePose and coverageScore.
class RefineModel {
public:
  /// Radius (mm) within which the cloud constructor estimates normals.
  static constexpr double kNormalRadiusMm = 3.0;

  /// Estimates normals on all valid points of `model_mm` (PCA of up to 12 neighbours within
  /// kNormalRadiusMm, or the cloud's own normals if it has them), turns them towards the teach
  /// camera, then keeps at most `max_points` (> 0) points: one per cell of the finest voxel grid
  /// that gives no more than that, the one nearest the cell centre. `viewpoint_model_mm` is the
  /// teach camera in the model frame (TaughtModel: T_teach_model.inverse().translation()); without
  /// it the camera is taken to look along +z from far away (the model frame has the teach camera's
  /// axes). Points whose normal cannot be estimated are dropped. Throws Error when the cloud has no
  /// valid point or fewer than 3 points with a normal.
  RefineModel(const PointCloud& model_mm, int max_points,
              const std::optional<Eigen::Vector3d>& viewpoint_model_mm = std::nullopt);
  /// The same from the model's points already indexed with their normals (`surface`, built with
  /// the options the constructor above uses, or others the caller wants), so that one index
  /// serves verification and refinement. Throws as above.
  RefineModel(std::shared_ptr<const SceneIndex> surface, int max_points);

  [[nodiscard]] const std::vector<Eigen::Vector3f>& points() const { return m_points; }
  [[nodiscard]] const std::vector<Eigen::Vector3f>& normals() const { return m_normals; }
  [[nodiscard]] std::size_t size() const { return m_points.size(); }
  /// Largest distance of a kept point from their centroid (mm): turns rotation steps into
  /// displacements for the convergence test.
  [[nodiscard]] double radius_mm() const { return m_radius_mm; }
  /// Edge of the voxel grid used for the subsample (mm); 0 when every point was kept.
  [[nodiscard]] double voxel_mm() const { return m_voxel_mm; }
  /// All valid points of the model with the normals estimated above, indexed: the model's own
  /// surface as its teach camera saw it (the near-symmetry search fits turns of the view to it).
  [[nodiscard]] const SceneIndex& surface() const { return *m_surface; }

private:
  std::shared_ptr<const SceneIndex> m_surface;
  std::vector<Eigen::Vector3f> m_points;
  std::vector<Eigen::Vector3f> m_normals;
  double m_radius_mm = 0;
  double m_voxel_mm = 0;
};

} // namespace scanpick::core
