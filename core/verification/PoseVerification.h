#pragma once
/// @file PoseVerification.h
/// Point-level verification of a pose (beyond the thesis): how much of the model the scan
/// confirms at that pose, how much it contradicts, and how much it cannot see.
///
/// Module core/verification (scanpick::core_verification), hypothesis verification. Contract: a
/// pose hypothesis of a taught view (VerifyModel) is tallied and scored against one scan
/// (VerifyScene: the indexed scene, the organized scan, its sensor, floor and projector shadows);
/// the answer depends on the model, the scan and the pose alone, not on how the pose was found or
/// what is done with it. It uses base, keypoints, matching (the revolved body), model and refine
/// (SceneIndex), and nothing of the Recognizer.

#include "core/cloud/PointCloud.h"
#include "core/cloud/Sensor.h"
#include "core/keypoints/Keypoints.h"
#include "core/matching/RevolutionAxis.h"
#include "core/model/TaughtModel.h"
#include "core/refine/SceneIndex.h"

#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace scanpick::core {

/// The model's points for verification (model frame, mm), their unit normals facing the teach
/// camera (NaN where none could be estimated) and its keypoints (edges), each evenly strided.
struct VerifyModel {
  std::vector<Eigen::Vector3f> points, normals;
  std::vector<Eigen::Vector3f> keypoints;
  /// For a view of a surface of revolution, the body it stands for (null otherwise): which of its
  /// unmeasured points the part itself hides from the camera or the projector.
  std::shared_ptr<const RevolvedBody> body;
  /// The points cover the part's every side (TaughtModel::all_around): at any pose about half of
  /// them face away, and verification expects only the others.
  bool all_around = false;
  /// Of a model seen from every side: the spacing of `points` (mm), for the points its own body
  /// hides at a pose (selfHidden); 0 otherwise.
  double spacing_mm = 0.0;
};

/// Every valid point of `model`, strided to at most about `points`, with its normal (PCA within
/// `normal_radius_mm`; wire-like models such as the thesis's ideal part have none and are verified
/// by position alone), and at most about 400 of its keypoints.
std::shared_ptr<const VerifyModel> makeVerifyModel(const TaughtModel& model, int points,
                                                   double normal_radius_mm);
/// The same from the model's points already indexed (modelSurface), which refinement can share.
/// Only the normals of every verifyModelStride()-th indexed point are read.
std::shared_ptr<const VerifyModel> makeVerifyModel(const TaughtModel& model,
                                                   const SceneIndex& model_surface, int points);
/// The stride makeVerifyModel takes through `valid_points` points to keep about `points`.
std::size_t verifyModelStride(std::size_t valid_points, int points);
/// The model's valid points indexed with their normals (PCA within `normal_radius_mm`, facing the
/// teach camera; a model seen from every side, TaughtModel::all_around, keeps its own outward
/// ones), as verification uses them.
std::shared_ptr<const SceneIndex> modelSurface(const TaughtModel& model, double normal_radius_mm);

/// The scene's keypoints (of every object) indexed, for the edge check of verification.
struct EdgeCheck {
  const SceneIndex* scene_keypoints = nullptr; ///< null: no edge check
  double tolerance_mm = 0.0;
};

/// Every object's keypoints in one cloud, for EdgeCheck::scene_keypoints. Keypoints are scan
/// points: when each projects into its own pixel of `sensor` (a point found twice counted once),
/// the cloud is organized as the sensor's image with them at their pixels, so that the edge check
/// looks in pixel windows when it is indexed with the sensor (SceneIndexOptions::sensor);
/// otherwise it is a plain list.
PointCloud edgeKeypointCloud(const std::vector<Keypoints>& keypoints, const SensorModel& sensor);

/// What the scan says about a set of model points at one pose.
struct PointTally {
  std::size_t points = 0;     ///< model points looked at
  std::size_t confirmed = 0;  ///< a scene point facing the same way lies within the tolerance
  std::size_t violations = 0; ///< the camera sees clearly behind the point: nothing is there
  std::size_t hidden = 0;     ///< turned away from the camera, or behind something else
  /// Whose normal faces away from the camera, wherever else they are counted (the floor test
  /// comes first): a model of every side expects only the others.
  std::size_t turned_away = 0;
  /// Of a model seen from every side: facing the camera, but behind its own body (selfHidden).
  std::size_t self_hidden = 0;
  /// Unmeasured, and the projector's light to it is blocked by measured surface (the inside of
  /// an upright cup behind its rim): the scan can say nothing about it.
  std::size_t shadowed = 0;
};

/// Whether a tally of points may stop (tallyPoints): given the tally so far and the points left.
using TallyStop = std::function<bool(const PointTally& so_far, std::size_t left)>;

/// What tallyPoints looks at, and how far.
struct TallyOptions {
  /// Indices of the model points to look at; null: every point.
  const std::vector<std::uint32_t>* subset = nullptr;
  /// Asked every few points with the tally so far and the number of points left: true ends the
  /// tally there (it then counts the points looked at). Empty: the tally runs to the end.
  TallyStop stop;
  /// False for a caller that counts only confirmations and violations: points without a
  /// measurement are then neither hidden nor shadowed, and their walks through the model's body
  /// are saved.
  bool sort_unmeasured = true;
};

/// Where a structured-light scan's projector light reached: for each projector pixel, the depth
/// (along the projector's axis) of the nearest measured point. A point without a measurement lay
/// in the projector's shadow when measured surface lies between the projector and it (the inside
/// of a cup behind its rim).
class ProjectorShadow {
public:
  /// Projects every valid point of `scan` (scene frame = camera frame, mm) into the projector,
  /// modelled as a pinhole with the camera's intrinsics at sensor.T_camera_projector.
  ProjectorShadow(const PointCloud& scan, const SensorModel& sensor);
  /// True when measured surface lies more than `margin_mm` nearer to the projector than `p`
  /// (scene frame) on its ray, within a pixel.
  [[nodiscard]] bool shadowed(const Eigen::Vector3f& p, float margin_mm) const;

private:
  /// The projector pixel of `p` (scene frame) and its depth along the projector's axis; nothing
  /// behind the projector.
  [[nodiscard]] std::optional<std::pair<Eigen::Vector2i, float>>
  projectorPixel(const Eigen::Vector3f& p) const;

  Eigen::Isometry3f m_T_projector_scene;
  SensorModel m_sensor;          ///< its intrinsics stand for the projector's
  std::vector<float> m_depth_mm; ///< nearest measured depth per projector pixel; +inf: none
};

/// The scene a pose is verified against: its indexed points, the organized scan itself (for the
/// look-through test), the camera that took it (at the scene frame's origin) and, when known, the
/// floor the parts rest on.
struct VerifyScene {
  const SceneIndex* index = nullptr;
  const PointCloud* scan = nullptr;
  const SensorModel* sensor = nullptr;
  /// The floor (or table) plane, (a, b, c, d) with a unit normal towards the camera
  /// (FloorRemovalResult::resting_plane); none: no floor test.
  std::optional<Eigen::Vector4f> floor_plane;
  /// The scan's projector shadows; none: unmeasured points are expected like any other.
  const ProjectorShadow* shadow = nullptr;
};

/// Tallies the model points listed in `subset` (indices into model.points; all when null) at pose
/// `T_scene_model`. A point is confirmed when a scene point whose normal agrees within 60° lies
/// within `tolerance_mm`. Otherwise, on an organized scan of the sensor's size, it is a violation
/// when the camera sees the scene more than 3 x tolerance behind it at its pixel (it looks through
/// where the pose puts material: a hole, or the floor beside a part), and hidden when the camera
/// sees something that much in front of it (another part); points turned away are hidden too.
/// A point more than 3 x tolerance below the scene's floor plane is a violation wherever the scan
/// is: no part reaches into the floor it rests on. A point whose pixel has no measurement is
/// hidden when the model's own body lies between it and the camera, and shadowed when scene.shadow
/// says the projector's light to it was blocked or the model's body lies between it and the
/// projector.
/// `options` chooses the points, a stop for a caller that needs the tally only while it can still
/// reach something, and whether unmeasured points are sorted.
PointTally tallyPoints(const VerifyModel& model, const VerifyScene& scene,
                       const Eigen::Isometry3d& T_scene_model, double tolerance_mm,
                       const TallyOptions& options = {});

/// The highest surface score (verifyPose's, before the edge agreement) that a tally can still
/// reach with `left` points not looked at: each of them confirmed, and the expected count at its
/// lowest (75 % of the points not shadowed so far and, with `all_around`, not turned away).
double surfaceScoreBound(const PointTally& tally, std::size_t left, bool all_around = false);

/// How well the scan bears out the points `subset` of `part` (all when null) at `T_scene_model`:
/// (confirmed − violations) ÷ the points neither hidden nor shadowed (tallyPoints), 0 when there
/// are none. Unlike verifyPose it has no lower bound on the expected count and no edge check: it
/// compares poses of one instance on the same points (a view's and those of the views joined to
/// it), whose other sides confirm or contradict a pose where the view's own points cannot.
double wholePartScore(const VerifyModel& part, const VerifyScene& scene,
                      const Eigen::Isometry3d& T_scene_model, double tolerance_mm,
                      const std::vector<std::uint32_t>* subset = nullptr);

/// Every stride-th index of `count` points, so that about `target` remain (all when fewer).
std::vector<std::uint32_t> evenSubset(std::size_t count, std::size_t target);

/// Verification score in [0, 1]: (confirmed − violations) ÷ the points expected to be seen,
/// times the edge agreement (the share of model keypoints on confirmed surface with a scene
/// keypoint within edges.tolerance_mm: a flat face matched onto another at a wrong turn confirms
/// its surface but not its outline). Shadowed points count for nothing. The expected count is
/// never taken below 75 % of the points not shadowed, so a pose that turns the taught side away (a
/// flip), or is confirmed on one leg of a bracket whose other leg falls behind other parts, cannot
/// score on the few points left. A model seen from every side (VerifyModel::all_around) expects
/// only the points that face the camera within 65°, and has no edge check: its keypoints are not
/// the edges a scan shows.
/// A caller that drops every pose scoring under `drop_below` lets verification stop looking at a
/// pose's points once its surface can no longer score `drop_below` (surfaceScoreBound), and skip
/// the edge check of a pose whose surface alone scores under it: that pose gets the bound or its
/// surface score, no lower than its full score and still under `drop_below`. Scores from
/// `drop_below` up are the full ones.
double verifyPose(const VerifyModel& model, const VerifyScene& scene,
                  const Eigen::Isometry3d& T_scene_model, double tolerance_mm,
                  const EdgeCheck& edges, double drop_below = 0.0);

} // namespace scanpick::core
