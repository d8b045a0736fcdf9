#pragma once
/// @file Part.h
/// A part the virtual scanner can drop into a bin: its closed mesh, grip points and symmetries.

#include "core/common/GripPoint.h"
#include "core/sim/Mesh.h"

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

namespace scanpick::core {

/// An axis of continuous rotational symmetry, in the part frame.
struct SymmetryAxis {
  Eigen::Vector3d point_mm = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ(); ///< unit vector
};

/// The part's symmetries: `part ≡ part · S` for every S in `discrete` (identity excluded), and for
/// every rotation about `continuous_axis` when set.
struct PartSymmetry {
  std::optional<SymmetryAxis> continuous_axis;
  std::vector<Eigen::Isometry3d> discrete;
};

/// A rigid part in millimetres. Its surface is the union of `components`, each a closed,
/// outward-oriented mesh (they may overlap). Physics uses the convex hull of each component, which
/// contains the component, so instances cannot interpenetrate once their hulls do not.
struct Part {
  std::string name; ///< "support", "cup", ... or the mesh file's stem
  std::vector<TriangleMesh> components;
  std::vector<GripPoint> grip_points;
  PartSymmetry symmetry;
  /// Rotation of the part frame that gives its natural resting pose on a table (for teach scenes).
  Eigen::Matrix3d R_table_part = Eigen::Matrix3d::Identity();

  /// All components in one mesh.
  [[nodiscard]] TriangleMesh mesh() const { return merged(components); }
  /// Largest distance between two vertices' bounding box corners (box diagonal), mm.
  [[nodiscard]] double diameter_mm() const;
  /// Centre of the part's bounding box, part frame.
  [[nodiscard]] Eigen::Vector3d center_mm() const;
};

} // namespace scanpick::core
