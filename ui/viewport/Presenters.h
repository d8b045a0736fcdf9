#pragma once
/// @file Presenters.h
/// VTK actors for core types: point clouds, keypoints, features (lines as segments, circles as
/// rings), grip points (small axes) and detections. GUI thread only. Sizes in VTK are device
/// pixels, so every pixel size here is given in logical pixels and multiplied by `ratio`.

#include "core/cloud/PointCloud.h"
#include "core/features/Feature.h"
#include "core/pipeline/Detection.h"

#include <Eigen/Geometry>
#include <QColor>
#include <vector>
#include <vtkSmartPointer.h>

class vtkActor;

namespace scanpick::ui {

/// Points as a vertex cloud in one colour, or coloured by depth (z) from blue to amber when
/// `by_depth`. Invalid (NaN) points are skipped. Points are mapped by `T` (mm).
vtkSmartPointer<vtkActor>
makeCloudActor(const core::PointCloud& cloud_mm, const QColor& colour, double point_size_px,
               double ratio, bool by_depth = false,
               const Eigen::Isometry3d& T = Eigen::Isometry3d::Identity());

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

/// Small axes (x red, y green, z blue, `length_mm` long) at each grip point, oriented by `T`'s
/// rotation; the positions are already in the frame shown.
vtkSmartPointer<vtkActor> makeGripAxesActor(const std::vector<core::GripPoint>& grips,
                                            double length_mm, double ratio,
                                            const Eigen::Matrix3d& R = Eigen::Matrix3d::Identity());

/// A distinct, saturated colour for detection `index` (golden-ratio hue steps).
QColor detectionColour(int index);

} // namespace scanpick::ui
