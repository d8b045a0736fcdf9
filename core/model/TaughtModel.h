#pragma once
/// @file TaughtModel.h
/// The taught model (thesis §3.5, first paragraph): the part cropped from a scan, its keypoints
/// and features, the parameters it was taught with, and the operator's grip points.

#include "core/cloud/PointCloud.h"
#include "core/cloud/Sensor.h"
#include "core/cloud/Units.h"
#include "core/common/GripPoint.h"
#include "core/common/Progress.h"
#include "core/features/Feature.h"
#include "core/model/AutoParams.h"
#include "core/params/Parameters.h"
#include "core/params/ViewParams.h"

#include <Eigen/Geometry>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace scanpick::core {

/// Another view of the same part, moved into a model's frame (joinViews): what that view's teach
/// scan saw of the part, which this model's own scan may not have (a cup's handle from the front).
struct JoinedView {
  std::string teach_scan;    ///< the view's teach scan file, for messages
  PointCloud cloud_mm;       ///< its cropped part, in this model's frame
  Eigen::Vector3d camera_mm; ///< its teach camera, in this model's frame (its normals face it)
};

/// A part taught from one scan. The model frame has the teach camera's axes and its origin at the
/// centroid of the cropped cloud, so a detection's translation is where that centroid lies.
struct TaughtModel {
  std::string name = "part";
  PointCloud cloud_mm;                               ///< the cropped part, model frame, unorganized
  std::vector<Eigen::Vector3f> keypoints_mm;         ///< first-level keypoints, model frame
  FeatureList features;                              ///< lines and circles, model frame
  RecognitionParams params;                          ///< parameters it was taught with
  std::vector<GripPoint> grip_points;                ///< model frame, mm
  SensorModel sensor;                                ///< sensor of the teach scan
  LengthUnit source_units = LengthUnit::Millimetres; ///< units of the teach scan's file
  /// The model frame in the teach scan's (camera) frame: a pure translation to the centroid.
  Eigen::Isometry3d T_teach_model = Eigen::Isometry3d::Identity();
  /// The model frame in the part's own frame, when the part's pose in the teach scan was known
  /// (TeachOptions::T_scan_part): views of one part that have it can be joined (joinViews).
  std::optional<Eigen::Isometry3d> T_part_model;
  /// The other views of the part joined into this one (joinViews); not kept in the model file.
  std::vector<JoinedView> joined_views;
  /// The largest distance between two of the cloud's points, flying pixels left out
  /// (PartMeasures::diameter_mm): the same however the part lay when taught. Sizes the radii of
  /// duplicate suppression and of the merge of views.
  double diameter_mm = 0.0;
  /// File name of the scan it was taught from ("" when unknown): tells views of one part apart
  /// and lets the evaluator find the teach scene's ground truth.
  std::string teach_scan;
  /// Matching parameters this view sets for itself, in place of the recognition parameters'
  /// (empty: none). E.g. a lower matching.min_coverage for a thin plate seen edge-on, whose edge
  /// normals agree with a scan's only in part (docs/design-notes.md, "A view's own parameters").
  ViewParams view_params;
  /// Why each parameter derived for this part has its value (autoTeachParams), by key; empty when
  /// the parameters were given.
  std::map<std::string, std::string> param_reasons;
  /// The crop is the part seen from every side, not one view (an unorganized cloud that fails
  /// seenFromOneCamera): merged scans or points sampled on a mesh. Its cloud then carries normals
  /// turned out of the part (outwardNormals), which verification and refinement take as they are
  /// instead of turning them towards the teach camera, and it covers every viewing direction.
  bool all_around = false;
};

/// A box in the scan frame given by its pose and half extents (an operator's rotated crop box).
struct OrientedBox {
  Eigen::Isometry3f T_scan_box = Eigen::Isometry3f::Identity();
  Eigen::Vector3f half_extents_mm = Eigen::Vector3f::Zero();
};

/// How to cut the part out of the teach scan.
struct TeachOptions {
  std::string name = "part";
  std::optional<Eigen::AlignedBox3f> crop_box_mm; ///< axis-aligned crop in the scan frame
  std::optional<OrientedBox> crop_oriented;       ///< or an oriented one (used if set)
  /// Run floor removal (params.floor) on the whole scan before cropping (the table is its
  /// dominant plane there; inside a tight crop a flat face of the part could be taken instead).
  bool remove_floor = false;
  std::vector<GripPoint> grips_scan; ///< grip points in the scan frame, mm
  /// The part's pose in the scan frame, when known (a teach scene's ground truth): the model then
  /// knows its place in the part (TaughtModel::T_part_model).
  std::optional<Eigen::Isometry3d> T_scan_part;
  SensorModel sensor; ///< sensor of the scan (stored with the model)
  LengthUnit source_units = LengthUnit::Millimetres;
};

/// Smallest crop accepted by teach(), in points.
inline constexpr std::size_t kMinTeachPoints = 100;

/// The part cut out of `scan_mm` as teach() cuts it: floor removal (with options.remove_floor:
/// the plane the part rests on, found in the whole scan), crop, downsampling (params.downsample);
/// unorganized, scan frame. Throws Error without a crop box or when the crop holds fewer than
/// kMinTeachPoints points.
PointCloud cropPart(const PointCloud& scan_mm, const TeachOptions& options,
                    const RecognitionParams& params, const ProgressFn& progress = {});

/// Parameters for teaching and recognizing this part, derived from the scan around the crop (its
/// point spacing and noise) and from the part cut out with them (its size); `base` gives every
/// value not derived. Throws Error as cropPart does, or when the crop's points coincide.
AutoParams autoTeachParams(const PointCloud& scan_mm, const TeachOptions& options,
                           const RecognitionParams& base = {}, const ProgressFn& progress = {});

/// Teaches a model from `scan_mm` (camera frame): crop, optional floor removal, downsampling
/// (params.downsample), keypoints and features as for a scene object, then moves everything into
/// the model frame. Throws Error when neither crop is given, the crop holds fewer than
/// kMinTeachPoints points ("the crop holds N points: widen the crop box") or fewer than two
/// features are found ("found 1 feature: lower ransac size or widen the crop"); Cancelled when
/// `progress` asks to stop. Deterministic for a given params.seed.
TaughtModel teach(const PointCloud& scan_mm, const TeachOptions& options,
                  const RecognitionParams& params, const ProgressFn& progress = {});

/// Joins views of one part: each model that knows its place in the part (T_part_model) gets, in
/// joined_views, the clouds of the other models of the same name that know theirs, moved into its
/// own frame. Models returned in the order given; a joined one is a new copy, the others are the
/// models given.
std::vector<std::shared_ptr<const TaughtModel>>
joinViews(const std::vector<std::shared_ptr<const TaughtModel>>& models);

/// The pose of a part in a scan from its position (mm) and a unit quaternion (qw, qx, qy, qz), as
/// an operator gives it for TeachOptions::T_scan_part (a fixture, or the robot that placed the
/// part). Throws Error when the quaternion's length is off 1 by more than 0.001; it is normalized
/// otherwise.
Eigen::Isometry3d partPose(const Eigen::Vector3d& position_mm, const Eigen::Quaterniond& q);
/// The same from text as an operator types it: "x, y, z, qw, qx, qy, qz" (mm, then the
/// quaternion). Throws Error for anything but seven numbers separated by commas, and as above.
Eigen::Isometry3d partPose(const std::string& text);

/// Throws Error naming the first two names that differ when `models` are not all views of one
/// part: the models searched together (recognizeViews) must be.
void requireOnePart(const std::vector<std::shared_ptr<const TaughtModel>>& models);

/// The parameters a scene is searched with for `models` (views of one part, not empty): the first
/// view's, with the smallest of the views' floor distances: a view taught lying flat and thin
/// keeps its points in the bin.
RecognitionParams viewsParams(const std::vector<std::shared_ptr<const TaughtModel>>& models);

/// Points of `cloud` inside the oriented box (unorganized, channels follow).
PointCloud cropToOrientedBox(const PointCloud& cloud, const OrientedBox& box);

} // namespace scanpick::core
