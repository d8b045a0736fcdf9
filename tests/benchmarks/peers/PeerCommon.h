#pragma once
/// @file PeerCommon.h
/// What the peer recognizers of peers_bench share: the taught views as they see them, the scene
/// prepared once for both, and the final scoring and overlap suppression that turns refined pose
/// hypotheses into detections. Not part of the product (docs/peers.md).

#include "core/cloud/PointCloud.h"
#include "core/model/TaughtModel.h"

#include <Eigen/Geometry>
#include <cstddef>
#include <memory>
#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <string>
#include <vector>

namespace scanpick::peers {

/// One taught view (a `.spmodel`), in its model frame, millimetres.
struct PeerModel {
  std::string path; ///< the .spmodel file, as given
  const core::TaughtModel* taught = nullptr;
  core::PointCloud cloud_mm;   ///< the taught crop, every point, with normals
  core::PointCloud sampled_mm; ///< the crop voxel-sampled at PeerSettings::voxel_mm
  double diameter_mm = 0.0;    ///< bounding-box diagonal of the crop
};

/// Lengths every method of one part shares, from the part's views.
struct PeerSettings {
  double spacing_mm = 0.0;  ///< median nearest-neighbour distance of the first view's crop
  double diameter_mm = 0.0; ///< the largest view diameter
  /// The voxel edge the scene and the sampled models are brought to: the larger of the point
  /// spacing and a hundredth of the diameter.
  double voxel_mm = 0.0;
};

/// The scene after the preparation both peers get: the floor planes removed as the first view's
/// parameters say (core removeFloor), cut to the rectangle the bin's floor spans when removeFloor
/// found one (less a 5 mm margin: the walls go), voxel-sampled at PeerSettings::voxel_mm,
/// normals estimated (PCL, radius 3 voxels) and turned towards the camera at the origin.
struct PeerScene {
  pcl::PointCloud<pcl::PointXYZ>::Ptr points;
  pcl::PointCloud<pcl::Normal>::Ptr normals;
  pcl::KdTreeFLANN<pcl::PointXYZ> tree; ///< over `points`
};

/// A pose a method proposes for a view, after its own refinement.
struct Hypothesis {
  std::size_t view = 0;
  Eigen::Isometry3d T_scene_model = Eigen::Isometry3d::Identity();
};

/// A scored detection.
struct PeerDetection {
  Hypothesis hypothesis;
  double score = 0.0; ///< share of the view's points facing the camera that the scene confirms
};

/// Loads the views (normals as core::RefineModel estimates them) and derives the shared lengths.
/// Throws core::Error for an unreadable model or one whose normals cannot be estimated.
std::vector<PeerModel> loadPeerModels(const std::vector<std::string>& paths,
                                      std::vector<core::TaughtModel>& storage,
                                      PeerSettings& settings);

/// Prepares a scene (see PeerScene). `first` gives the floor-removal parameters and seed.
PeerScene prepareScene(const core::PointCloud& scene_mm, const core::TaughtModel& first,
                       const PeerSettings& settings);

/// Scores each hypothesis (share of the view's sampled points facing the camera that have a scene
/// point within `settings.voxel_mm`), drops those below `min_score`, then, best first, drops
/// each whose confirmed scene points are more than half confirmed by a detection kept already.
std::vector<PeerDetection> scoreAndSuppress(const std::vector<Hypothesis>& hypotheses,
                                            const std::vector<PeerModel>& models,
                                            const PeerScene& scene, const PeerSettings& settings,
                                            double min_score);

/// What a method proposes for one scene, with its own timings (ms).
struct MethodOutput {
  std::vector<Hypothesis> hypotheses;
  double matching_ms = 0.0; ///< descriptors, voting or grouping
  double refine_ms = 0.0;   ///< the method's own ICP
};

/// A peer recognizer: trained once on a part's views, then run on each prepared scene.
class PeerMethod {
public:
  virtual ~PeerMethod() = default;
  /// Builds the method's model of each view (not counted in a scene's time).
  virtual void train(const std::vector<PeerModel>& models, const PeerSettings& settings) = 0;
  /// Pose hypotheses for every view in `scene`, each refined by the method's own ICP.
  virtual MethodOutput detect(const PeerScene& scene) = 0;
  /// One line naming the parameters used, for the log.
  virtual std::string describe() const = 0;
};

/// The scene-side parameters of PPF3DDetector::match.
struct OpenCvPpfOptions {
  double scene_sample_step = 1.0 / 40.0; ///< share of the sampled scene points used as references
  double scene_distance = 0.05;          ///< scene sampling step, times the model's diameter
};

/// OpenCV's surface matching: cv::ppf_match_3d::PPF3DDetector (Drost 2010) and its ICP, with the
/// values of OpenCV's own sample (ppf_load_match.cpp) by default; see PeerOpenCvPpf.cpp.
std::unique_ptr<PeerMethod> makeOpenCvPpf(const OpenCvPpfOptions& options);

/// PCL's correspondence grouping as in its tutorial: uniform-sampling keypoints, SHOT
/// descriptors, kd-tree correspondences, pcl::GeometricConsistencyGrouping, then
/// pcl::IterativeClosestPoint; see PeerPclGrouping.cpp.
std::unique_ptr<PeerMethod> makePclGrouping();

} // namespace scanpick::peers
