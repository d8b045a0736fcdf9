#pragma once
/// @file Presenters.h
/// VTK actors for core types: point clouds, keypoints, features (lines as segments, circles as
/// rings), grip points (axes and markers) and detections (their ID labels). GUI thread only. Sizes
/// in VTK are device pixels, so every pixel size here is given in logical pixels and multiplied by
/// `ratio`.

#include "core/cloud/PointCloud.h"
#include "core/common/Detection.h"
#include "core/features/Feature.h"

#include <Eigen/Geometry>
#include <QColor>
#include <vector>
#include <vtkSmartPointer.h>

class QString;
class vtkActor;
class vtkProp;

namespace scanpick::ui {

/// How makeCloudActor colours points; depth is z in the cloud's own frame (the camera's, for a
/// scan), spread over the cloud's z range.
enum class CloudShading {
  Flat,      ///< the one colour given
  Depth,     ///< amber (near) to blue (far): the teach views
  DepthGrey, ///< light (near) to dark grey (far): a scene under coloured detections
};

/// Most points makeCloudActor draws: a whole scan (a PhoXi M has 800,000) is thinned evenly to
/// this, which looks the same at screen resolution and keeps each frame cheap for the GUI thread.
inline constexpr std::size_t kMaxDrawnPoints = 150000;

/// Points as a vertex cloud, shaded as `shading` says. Invalid (NaN) points are skipped; of a
/// cloud with more than `max_points` valid points, every k-th is drawn. Points are mapped by `T`
/// (mm).
vtkSmartPointer<vtkActor> makeCloudActor(const core::PointCloud& cloud_mm, const QColor& colour,
                                         double point_size_px, double ratio,
                                         CloudShading shading = CloudShading::Flat,
                                         const Eigen::Isometry3d& T = Eigen::Isometry3d::Identity(),
                                         std::size_t max_points = kMaxDrawnPoints);

/// A set of points (e.g. keypoints) in one colour.
vtkSmartPointer<vtkActor>
makePointsActor(const std::vector<Eigen::Vector3f>& points_mm, const QColor& colour,
                double point_size_px, double ratio,
                const Eigen::Isometry3d& T = Eigen::Isometry3d::Identity());

/// Lines as segments (centre ± direction·length/2) and circles as 48-segment rings in the plane
/// normal to their direction, mapped by `T`.
vtkSmartPointer<vtkActor>
makeFeaturesActor(const core::FeatureList& features, const QColor& line_colour,
                  const QColor& circle_colour, double line_width_px, double ratio,
                  const Eigen::Isometry3d& T = Eigen::Isometry3d::Identity());

/// Axes (x red, y green, z blue, `length_mm` long, 4 px wide) at each grip point: the tool frame
/// of a grip point taught with an approach (z the approach, x the closing axis;
/// core::grasp::toolPose), otherwise oriented by `R`. Positions and directions are already in the
/// frame shown.
vtkSmartPointer<vtkActor> makeGripAxesActor(const std::vector<core::GripPoint>& grips,
                                            double length_mm, double ratio,
                                            const Eigen::Matrix3d& R = Eigen::Matrix3d::Identity());

/// A round marker (`size_px` across, drawn as a sphere) at each grip point, in `colour`.
vtkSmartPointer<vtkActor> makeGripMarkersActor(const std::vector<core::GripPoint>& grips,
                                               const QColor& colour, double size_px, double ratio);

/// `text` at `position_mm`, in bold `colour` on a dark box with a `colour` frame, drawn over the
/// scene (a 2D overlay anchored at that point): a detection's ID.
vtkSmartPointer<vtkProp> makeLabelActor(const QString& text, const Eigen::Vector3d& position_mm,
                                        const QColor& colour, int font_px, double ratio);

/// Detection `index`'s colour (core::detectionColour), the one every view and the result picture
/// use.
QColor detectionColour(int index);

} // namespace scanpick::ui
