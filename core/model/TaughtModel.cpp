#include "core/model/TaughtModel.h"

#include "core/common/Error.h"
#include "core/features/FeatureExtraction.h"
#include "core/keypoints/Keypoints.h"
#include "core/model/AllAround.h"
#include "core/model/AutoParams.h"
#include "core/preprocess/Downsample.h"
#include "core/preprocess/FloorRemoval.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace scanpick::core {

namespace {

/// The normals of a part seen from every side are fitted to at least this many point spacings.
constexpr double kNormalRadiusSpacings = 3.0;

/// `cloud` as `sensor` would measure it at its nominal distance: its spacing and noise at least
/// the sensor's (where the sensor model gives them).
ScanMeasures asScannedBy(ScanMeasures cloud, const SensorModel& sensor) {
  if (sensor.fx > 0 && sensor.nominal_distance_mm > 0)
    cloud.spacing_mm = std::max(cloud.spacing_mm, sensor.nominal_distance_mm / sensor.fx);
  cloud.noise_mm = std::max(cloud.noise_mm, sensor.noise_sigma_mm);
  return cloud;
}

/// Whether a point (scan frame, mm) is valid and lies in the crop of `options` (the oriented box
/// if set).
std::function<bool(const Eigen::Vector3f&)> cropTest(const TeachOptions& options) {
  if (options.crop_oriented) {
    const Eigen::Isometry3f T_box_scan = options.crop_oriented->T_scan_box.inverse();
    const Eigen::Vector3f half = options.crop_oriented->half_extents_mm;
    return [T_box_scan, half](const Eigen::Vector3f& p) {
      return isValid(p) && ((T_box_scan * p).cwiseAbs().array() <= half.array()).all();
    };
  }
  const Eigen::AlignedBox3f box = *options.crop_box_mm;
  return [box](const Eigen::Vector3f& p) { return isValid(p) && box.contains(p); };
}

} // namespace

PointCloud cropToOrientedBox(const PointCloud& cloud, const OrientedBox& box) {
  const Eigen::Isometry3f T_box_scan = box.T_scan_box.inverse();
  return selectPoints(cloud, [&](std::size_t i) {
    const auto& p = cloud.points_mm[i];
    return isValid(p) && ((T_box_scan * p).cwiseAbs().array() <= box.half_extents_mm.array()).all();
  });
}

namespace {

/// The floor under the crop of `options`, removed from `scan_mm` with `params.floor`. The floor is
/// found in the whole scan, where the table is the dominant plane: inside a tight crop a large
/// flat face of the part may hold more points than the table and would go instead. It is the
/// plane the part rests on (removeFloor with the crop as the part): a face that outnumbers the
/// table even so (a large plate's) has the table behind it.
FloorRemovalResult floorUnderCrop(const PointCloud& scan_mm, const TeachOptions& options,
                                  const RecognitionParams& params, const ProgressFn& progress) {
  FloorParams floor = params.floor;
  floor.enabled = true;
  const auto inCrop = cropTest(options);
  std::vector<char> cropped(scan_mm.size());
  for (std::size_t i = 0; i < scan_mm.size(); ++i)
    cropped[i] = inCrop(scan_mm.points_mm[i]);
  return removeFloor(scan_mm, floor, params.seed, progress, cropped);
}

/// The `fraction` quantile of `values` (reordered); `values` must not be empty.
double quantile(std::vector<double>& values, double fraction) {
  const auto at = values.begin() + std::ptrdiff_t(fraction * double(values.size() - 1));
  std::nth_element(values.begin(), at, values.end());
  return *at;
}

/// ScanMeasures::part_layer_mm: the 10th percentile of the heights above `plane` (the plane the
/// part rests on) of the crop's points higher than 4 x `noise_mm` (the table's own points lie
/// below), when at least kThinShare of them lie within `floor_mm` (a thin part lying flat, which
/// that floor distance would remove with the floor) and that layer stands clear of the table's
/// own spread (twice the 99th percentile |height| of the table's points outside the crop: a
/// sensor's depth steps on the table are not a part); else, with fewer than kMinTeachPoints such
/// points, 0.
double partLayer_mm(const PointCloud& scan_mm, const TeachOptions& options,
                    const Eigen::Vector4f& plane, double floor_mm, double noise_mm) {
  const auto inCrop = cropTest(options);
  std::vector<double> part_heights, table_heights;
  for (const Eigen::Vector3f& p : scan_mm.points_mm) {
    if (!p.allFinite())
      continue;
    const double h = plane.head<3>().dot(p) + plane[3];
    if (!inCrop(p)) {
      if (std::abs(h) <= floor_mm)
        table_heights.push_back(std::abs(h));
    } else if (h > 4.0 * noise_mm) {
      part_heights.push_back(h);
    }
  }
  constexpr double kThinShare = 0.2;
  const auto within = std::count_if(part_heights.begin(), part_heights.end(),
                                    [&](double h) { return h <= floor_mm; });
  if (part_heights.size() < kMinTeachPoints || table_heights.size() < kMinTeachPoints ||
      double(within) < kThinShare * double(part_heights.size()))
    return 0.0;
  const double layer = quantile(part_heights, 0.1);
  return layer > 2.0 * quantile(table_heights, 0.99) ? layer : 0.0;
}

/// The points of `source` (the scan, its floor removed or not) inside the crop of `options`,
/// downsampled to `voxel_mm`.
PointCloud cropOf(const PointCloud& source, const TeachOptions& options, double voxel_mm) {
  const auto inCrop = cropTest(options);
  PointCloud part =
      selectPoints(source, [&](std::size_t i) { return inCrop(source.points_mm[i]); });
  part = dropInvalid(voxelDownsample(part, voxel_mm));
  if (part.size() < kMinTeachPoints)
    throw Error("the crop holds " + std::to_string(part.size()) + " points (at least " +
                std::to_string(kMinTeachPoints) + " are needed): widen the crop box");
  return part;
}

/// Whether teach removes the floor of `scan_mm` before cropping.
bool removesFloor(const PointCloud& scan_mm, const TeachOptions& options) {
  return options.remove_floor && scan_mm.validCount() >= kMinTeachPoints;
}

void requireCrop(const TeachOptions& options) {
  if (!options.crop_box_mm && !options.crop_oriented)
    throw Error("no crop box given: draw a box around the part (or pass --crop-box)");
}

/// Whether `crop_mm`, cut from `scan_mm`, is the part seen from every side (merged scans, points
/// sampled on a mesh): never when the scan is organized, one camera's image however noisy its
/// depth (a Kinect's steps stack points along a line of sight); else when no one camera at the
/// origin could have taken it (seenFromOneCamera).
bool seenAllAround(const PointCloud& scan_mm, const PointCloud& crop_mm, double spacing_mm) {
  return !scan_mm.isOrganized() && !seenFromOneCamera(crop_mm, Eigen::Vector3d::Zero(), spacing_mm);
}

} // namespace

PointCloud cropPart(const PointCloud& scan_mm, const TeachOptions& options,
                    const RecognitionParams& params, const ProgressFn& progress) {
  scan_mm.validate();
  requireCrop(options);
  PointCloud part = removesFloor(scan_mm, options)
                        ? cropOf(floorUnderCrop(scan_mm, options, params, progress).remaining,
                                 options, params.downsample.voxel_mm)
                        : cropOf(scan_mm, options, params.downsample.voxel_mm);
  reportProgress(progress, 1.0);
  return part;
}

AutoParams autoTeachParams(const PointCloud& scan_mm, const TeachOptions& options,
                           const RecognitionParams& base, const ProgressFn& progress) {
  scan_mm.validate();
  requireCrop(options);
  const auto inCrop = cropTest(options);
  const PointCloud crop =
      selectPoints(scan_mm, [&](std::size_t i) { return inCrop(scan_mm.points_mm[i]); });
  ScanMeasures scan = measureScan(crop);
  if (!(scan.spacing_mm > 0))
    throw Error("the crop's points coincide (no spacing between them): crop a part of a scan");
  // A part seen from every side (merged scans, points sampled on a mesh) is searched in scans of
  // the sensor: its spacing and noise, at the least, are what the scenes will have.
  if (seenAllAround(scan_mm, crop, scan.spacing_mm))
    scan = asScannedBy(scan, options.sensor);
  const RecognitionParams flat = deriveScanParams(scan, base).params;
  if (!removesFloor(scan_mm, options)) {
    const PointCloud part = cropOf(scan_mm, options, flat.downsample.voxel_mm);
    return deriveParams(scan, measurePart(part, scan.spacing_mm), base);
  }
  // The floor found with the scan's own floor distance tells how thin the part lies; it is found
  // again only when that thinness moves the floor distance.
  FloorRemovalResult floor = floorUnderCrop(scan_mm, options, flat, progress);
  if (floor.resting_plane)
    scan.part_layer_mm =
        partLayer_mm(scan_mm, options, *floor.resting_plane, flat.floor.distance_mm, scan.noise_mm);
  const RecognitionParams scan_params = deriveScanParams(scan, base).params;
  if (scan_params.floor.distance_mm != flat.floor.distance_mm)
    floor = floorUnderCrop(scan_mm, options, scan_params, {});
  const PointCloud part = cropOf(floor.remaining, options, scan_params.downsample.voxel_mm);
  return deriveParams(scan, measurePart(part, scan.spacing_mm), base);
}

TaughtModel teach(const PointCloud& scan_mm, const TeachOptions& options,
                  const RecognitionParams& params, const ProgressFn& progress) {
  PointCloud part = cropPart(scan_mm, options, params, subProgress(progress, 0.0, 0.25));
  const double spacing_mm = measureScan(part).spacing_mm;
  // A part seen from every side has no camera its normals could face: they face out of it.
  const bool all_around = seenAllAround(scan_mm, part, spacing_mm);
  if (all_around)
    part.normals = outwardNormals(
        part, std::max(params.keypoints.normal_radius_mm, kNormalRadiusSpacings * spacing_mm));

  // Keypoints and features are found in the scan frame, as for scene objects (normals are
  // oriented towards the camera), then moved into the model frame.
  const Keypoints keypoints =
      extractKeypoints(part, params.keypoints, subProgress(progress, 0.25, 0.6));
  const FeatureExtraction extraction = extractFeatures(
      keypoints.points_mm, params.features, params.seed, subProgress(progress, 0.6, 0.95));
  // Feature matching needs two features; surface voting finds the part by its surface alone
  // (a cup's rim, split into arcs, gives it nothing), so a surface-voting model may have none.
  const std::size_t n = extraction.features.size();
  if (n < 2 && params.matching.surface_sampling_mm <= 0)
    throw Error("found " + std::to_string(n) + (n == 1 ? " feature" : " features") +
                " in the crop (" + std::to_string(keypoints.points_mm.size()) +
                " keypoints; matching needs at least 2): lower ransac size or widen the crop, "
                "or find the part by its surface (matching.surface_sampling_mm)");

  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& p : part.points_mm)
    centroid += p.cast<double>();
  centroid /= static_cast<double>(part.size());

  TaughtModel model;
  model.name = options.name;
  model.params = params;
  model.sensor = options.sensor;
  model.source_units = options.source_units;
  model.T_teach_model = Eigen::Isometry3d::Identity();
  model.T_teach_model.translation() = centroid;
  const Eigen::Isometry3f T_model_teach = model.T_teach_model.inverse().cast<float>();
  model.cloud_mm = transformed(part, T_model_teach);
  for (const auto& k : keypoints.points_mm)
    model.keypoints_mm.push_back(T_model_teach * k);
  model.features = extraction.features;
  for (auto& f : model.features)
    f.centre_mm = T_model_teach * f.centre_mm;
  for (const auto& g : options.grips_scan)
    model.grip_points.push_back(transformed(checkedGrip(g), model.T_teach_model.inverse()));
  if (options.T_scan_part)
    model.T_part_model = options.T_scan_part->inverse() * model.T_teach_model;
  model.diameter_mm =
      measurePart(model.cloud_mm, measureScan(model.cloud_mm).spacing_mm).diameter_mm;
  model.all_around = all_around;
  reportProgress(progress, 1.0);
  return model;
}

Eigen::Isometry3d partPose(const Eigen::Vector3d& position_mm, const Eigen::Quaterniond& q) {
  if (!(std::abs(q.norm() - 1.0) <= 1e-3) || !position_mm.allFinite())
    throw Error("the part pose's quaternion qw, qx, qy, qz has length " + std::to_string(q.norm()) +
                ": give a unit quaternion (and a finite position)");
  Eigen::Isometry3d T_scan_part = Eigen::Isometry3d::Identity();
  T_scan_part.linear() = q.normalized().toRotationMatrix();
  T_scan_part.translation() = position_mm;
  return T_scan_part;
}

Eigen::Isometry3d partPose(const std::string& text) {
  std::vector<double> p;
  std::stringstream fields(text);
  for (std::string field; std::getline(fields, field, ',');) {
    std::size_t used = 0;
    try {
      p.push_back(std::stod(field, &used));
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || field.find_first_not_of(" \t", used) != std::string::npos)
      throw Error("the part pose: '" + field + "' is not a number");
  }
  if (p.size() != 7)
    throw Error("the part pose needs 7 numbers separated by commas, x, y, z (mm), qw, qx, qy, qz; "
                "got " +
                std::to_string(p.size()));
  return partPose(Eigen::Vector3d(p[0], p[1], p[2]), Eigen::Quaterniond(p[3], p[4], p[5], p[6]));
}

void requireOnePart(const std::vector<std::shared_ptr<const TaughtModel>>& models) {
  for (const auto& model : models)
    if (model->name != models.front()->name)
      throw Error("models '" + models.front()->name + "' and '" + model->name +
                  "' are different parts: the models searched together must be views of one "
                  "part (recognize each part on its own)");
}

RecognitionParams viewsParams(const std::vector<std::shared_ptr<const TaughtModel>>& models) {
  RecognitionParams params = models.front()->params;
  for (const auto& model : models)
    params.floor.distance_mm = std::min(params.floor.distance_mm, model->params.floor.distance_mm);
  return params;
}

std::vector<std::shared_ptr<const TaughtModel>>
joinViews(const std::vector<std::shared_ptr<const TaughtModel>>& models) {
  std::vector<std::shared_ptr<const TaughtModel>> joined = models;
  for (std::size_t v = 0; v < models.size(); ++v) {
    const TaughtModel& view = *models[v];
    if (!view.T_part_model)
      continue;
    auto copy = std::make_shared<TaughtModel>(view);
    copy->joined_views.clear();
    for (std::size_t w = 0; w < models.size(); ++w) {
      const TaughtModel& other = *models[w];
      if (w == v || !other.T_part_model || other.name != view.name)
        continue;
      const Eigen::Isometry3d T_view_other = view.T_part_model->inverse() * *other.T_part_model;
      copy->joined_views.push_back({other.teach_scan,
                                    transformed(other.cloud_mm, T_view_other.cast<float>()),
                                    T_view_other * other.T_teach_model.inverse().translation()});
    }
    if (!copy->joined_views.empty())
      joined[v] = std::move(copy);
  }
  return joined;
}

} // namespace scanpick::core
