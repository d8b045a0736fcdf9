#pragma once
/// @file GroundTruth.h
/// What the evaluator needs from a ground-truth file (`<scene>.gt.json`, written by the virtual
/// scanner; format in docs/file-formats.md): the parts with their diameter, grip points and
/// symmetries, and the instances with their poses and visible fractions.

#include "core/sim/Scene.h"

#include <Eigen/Geometry>
#include <cstdint>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace scanpick::core::eval {

/// Highest ground-truth version this reader understands.
inline constexpr int kGroundTruthVersion = 1;

/// A named point, millimetres (frame given by the owner's field name).
struct NamedPoint {
  std::string name;
  Eigen::Vector3d position_mm = Eigen::Vector3d::Zero();
};

/// A rotation axis of continuous symmetry, in the part frame.
struct ContinuousAxis {
  Eigen::Vector3d point_mm = Eigen::Vector3d::Zero();   ///< a point on the axis
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ(); ///< unit direction
};

/// Symmetries of a part: `part ≡ part · S` for every discrete S (identity excluded), and any
/// rotation about the continuous axis when there is one.
struct PartSymmetry {
  std::optional<ContinuousAxis> continuous_axis;
  std::vector<Eigen::Isometry3d> discrete;
};

/// One part type of a scene.
struct PartInfo {
  std::string name;
  double diameter_mm = 0.0;                 ///< largest distance between two points of the part
  std::vector<NamedPoint> grip_points_part; ///< grip points in the part frame
  PartSymmetry symmetry;
};

/// One placed instance.
struct TruthInstance {
  int id = 0;
  std::string part; ///< key into GroundTruth::parts
  Eigen::Isometry3d T_scene_part = Eigen::Isometry3d::Identity();
  double visible_fraction = 1.0; ///< [0, 1], see file-formats.md
  long long visible_points = 0;
  /// The part's grip points in the scene frame, as the file gives them (may be empty).
  std::vector<NamedPoint> grip_points_scene = {};
};

/// A teach scene's crop box: the part lies within [min_mm, max_mm] of the box frame.
struct TruthCropBox {
  Eigen::Isometry3d T_scene_box = Eigen::Isometry3d::Identity();
  Eigen::Vector3d min_mm = Eigen::Vector3d::Zero(), max_mm = Eigen::Vector3d::Zero();
};

/// A ground-truth file's content.
struct GroundTruth {
  std::string source; ///< file it came from (for messages)
  std::string kind;   ///< "bin", "scatter" or "teach"
  std::uint64_t seed = 0;
  std::string cloud;         ///< scan file name, relative to the ground-truth file
  std::string sensor_preset; ///< sensor.preset ("phoxi-m-1032", ...; "" when absent)
  std::map<std::string, PartInfo> parts;
  std::vector<TruthInstance> instances;
  std::optional<TruthCropBox> crop_box; ///< teach scenes
  /// sensor.T_scene_world: the simulated world (its floor at z = 0, a bin centred on its origin)
  /// in the scene frame; none when not written.
  std::optional<Eigen::Isometry3d> T_scene_world;
  /// scene.bin (bin scenes); none when not written (ground truth written before it was).
  std::optional<BinGeometry> bin;
};

/// Validates and converts a parsed ground-truth document. Throws Error for a wrong format, a
/// future version, missing fields, non-finite numbers, non-rigid poses, instances of unknown
/// parts, a diameter that is not positive or a crop box whose minimum exceeds its maximum.
GroundTruth parseGroundTruth(const nlohmann::json& doc, const std::string& source);

/// Reads `path` (see parseGroundTruth; also throws Error for a missing or malformed file).
GroundTruth loadGroundTruth(const std::filesystem::path& path);

} // namespace scanpick::core::eval
