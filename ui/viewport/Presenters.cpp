#include "ui/viewport/Presenters.h"

#include "core/grasp/GraspPlanner.h"
#include "core/output/DetectionColours.h"

#include <QString>
#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <vtkActor.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCoordinate.h>
#include <vtkFloatArray.h>
#include <vtkIdTypeArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkUnsignedCharArray.h>

namespace scanpick::ui {
namespace {

vtkSmartPointer<vtkActor> actorFor(vtkPolyData* data, const QColor& colour, bool scalars) {
  auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  mapper->SetInputData(data);
  mapper->SetScalarVisibility(scalars);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(colour.redF(), colour.greenF(), colour.blueF());
  // Overlays should read as flat colours whatever the lighting.
  actor->GetProperty()->SetAmbient(1.0);
  actor->GetProperty()->SetDiffuse(0.0);
  actor->GetProperty()->SetSpecular(0.0);
  actor->GetProperty()->LightingOff();
  return actor;
}

Eigen::Vector3d map(const Eigen::Isometry3d& T, const Eigen::Vector3f& p) {
  return T * p.cast<double>();
}

/// Depth `z` (mm) between `z_min` (near: amber) and `z_max` (far: blue).
std::array<unsigned char, 3> depthColour(float z, float z_min, float z_max) {
  const float t = std::clamp((z - z_min) / (z_max - z_min), 0.0f, 1.0f);
  return {static_cast<unsigned char>(230 - 170 * t), static_cast<unsigned char>(170 - 40 * t),
          static_cast<unsigned char>(60 + 170 * t)};
}

/// Depth `z` (mm) between `z_min` (near: light grey) and `z_max` (far: dark grey).
std::array<unsigned char, 3> depthGrey(float z, float z_min, float z_max) {
  const float t = std::clamp((z - z_min) / (z_max - z_min), 0.0f, 1.0f);
  const auto v = static_cast<unsigned char>(225 - 150 * t);
  return {v, v, v};
}

/// Two unit vectors spanning the plane normal to `n`.
void planeBasis(const Eigen::Vector3d& n, Eigen::Vector3d& u, Eigen::Vector3d& v) {
  const Eigen::Vector3d helper =
      std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  u = n.cross(helper).normalized();
  v = n.cross(u).normalized();
}

} // namespace

vtkSmartPointer<vtkActor> makeCloudActor(const core::PointCloud& cloud, const QColor& colour,
                                         double point_size_px, double ratio, CloudShading shading,
                                         const Eigen::Isometry3d& T, std::size_t max_points) {
  const bool by_depth = shading != CloudShading::Flat;
  const bool grey = shading == CloudShading::DepthGrey;
  // The arrays are filled through their raw buffers: a whole scan (800,000 points) is drawn on
  // the GUI thread, which must stay responsive.
  std::size_t valid = 0;
  for (const Eigen::Vector3f& p : cloud.points_mm)
    valid += core::isValid(p) ? 1 : 0;
  // Every stride-th valid point: a whole scan is thinned evenly to at most max_points.
  max_points = std::max<std::size_t>(1, max_points);
  const std::size_t stride = std::max<std::size_t>(1, (valid + max_points - 1) / max_points);
  const auto n = static_cast<vtkIdType>((valid + stride - 1) / stride);
  float z_min = 0, z_max = 1;
  if (by_depth) {
    const Eigen::AlignedBox3f box = core::boundingBox(cloud);
    if (!box.isEmpty()) {
      z_min = box.min().z();
      z_max = std::max(box.max().z(), z_min + 1e-3f);
    }
  }
  auto coords = vtkSmartPointer<vtkFloatArray>::New();
  coords->SetNumberOfComponents(3);
  coords->SetNumberOfTuples(n);
  auto colours = vtkSmartPointer<vtkUnsignedCharArray>::New();
  colours->SetNumberOfComponents(3);
  colours->SetNumberOfTuples(by_depth ? n : 0);
  float* xyz = coords->GetPointer(0);
  unsigned char* rgb = colours->GetPointer(0);
  const Eigen::Matrix3f R = T.linear().cast<float>();
  const Eigen::Vector3f t = T.translation().cast<float>();
  const bool identity = T.isApprox(Eigen::Isometry3d::Identity());
  std::size_t seen = 0;
  for (const Eigen::Vector3f& p : cloud.points_mm) {
    if (!core::isValid(p) || seen++ % stride != 0)
      continue;
    const Eigen::Vector3f q = identity ? p : Eigen::Vector3f(R * p + t);
    *xyz++ = q.x();
    *xyz++ = q.y();
    *xyz++ = q.z();
    if (by_depth) {
      const auto [r, g, b] =
          grey ? depthGrey(p.z(), z_min, z_max) : depthColour(p.z(), z_min, z_max);
      *rgb++ = r;
      *rgb++ = g;
      *rgb++ = b;
    }
  }
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetData(coords);
  // One vertex cell per point: offsets 0..n, connectivity 0..n-1.
  auto offsets = vtkSmartPointer<vtkIdTypeArray>::New();
  offsets->SetNumberOfTuples(n + 1);
  std::iota(offsets->GetPointer(0), offsets->GetPointer(0) + n + 1, vtkIdType{0});
  auto connectivity = vtkSmartPointer<vtkIdTypeArray>::New();
  connectivity->SetNumberOfTuples(n);
  std::iota(connectivity->GetPointer(0), connectivity->GetPointer(0) + n, vtkIdType{0});
  auto verts = vtkSmartPointer<vtkCellArray>::New();
  verts->SetData(offsets, connectivity);
  auto data = vtkSmartPointer<vtkPolyData>::New();
  data->SetPoints(points);
  data->SetVerts(verts);
  if (by_depth)
    data->GetPointData()->SetScalars(colours);
  auto actor = actorFor(data, colour, by_depth);
  actor->GetProperty()->SetPointSize(static_cast<float>(point_size_px * ratio));
  return actor;
}

vtkSmartPointer<vtkActor> makePointsActor(const std::vector<Eigen::Vector3f>& points_mm,
                                          const QColor& colour, double point_size_px, double ratio,
                                          const Eigen::Isometry3d& T) {
  return makeCloudActor(core::PointCloud::fromPoints(points_mm), colour, point_size_px, ratio,
                        CloudShading::Flat, T);
}

vtkSmartPointer<vtkActor> makeFeaturesActor(const core::FeatureList& features,
                                            const QColor& line_colour, const QColor& circle_colour,
                                            double line_width_px, double ratio,
                                            const Eigen::Isometry3d& T) {
  constexpr int kRingSegments = 48;
  auto points = vtkSmartPointer<vtkPoints>::New();
  auto lines = vtkSmartPointer<vtkCellArray>::New();
  auto colours = vtkSmartPointer<vtkUnsignedCharArray>::New();
  colours->SetNumberOfComponents(3);
  const auto rgb = [](const QColor& c) {
    return std::array<unsigned char, 3>{static_cast<unsigned char>(c.red()),
                                        static_cast<unsigned char>(c.green()),
                                        static_cast<unsigned char>(c.blue())};
  };
  const auto line_rgb = rgb(line_colour), circle_rgb = rgb(circle_colour);
  for (const core::Feature& f : features) {
    const Eigen::Vector3d c = map(T, f.centre_mm);
    const Eigen::Vector3d d = (T.linear() * f.direction.cast<double>()).normalized();
    if (f.type == core::FeatureType::Line) {
      const Eigen::Vector3d a = c - d * (f.size_mm / 2.0), b = c + d * (f.size_mm / 2.0);
      lines->InsertNextCell(2);
      lines->InsertCellPoint(points->InsertNextPoint(a.data()));
      lines->InsertCellPoint(points->InsertNextPoint(b.data()));
      colours->InsertNextTypedTuple(line_rgb.data());
    } else {
      Eigen::Vector3d u, v;
      planeBasis(d, u, v);
      lines->InsertNextCell(kRingSegments + 1);
      const vtkIdType first = points->GetNumberOfPoints();
      for (int k = 0; k < kRingSegments; ++k) {
        const double a = 2.0 * M_PI * k / kRingSegments;
        const Eigen::Vector3d p = c + f.size_mm * (std::cos(a) * u + std::sin(a) * v);
        lines->InsertCellPoint(points->InsertNextPoint(p.data()));
      }
      lines->InsertCellPoint(first); // close the ring
      colours->InsertNextTypedTuple(circle_rgb.data());
    }
  }
  auto data = vtkSmartPointer<vtkPolyData>::New();
  data->SetPoints(points);
  data->SetLines(lines);
  data->GetCellData()->SetScalars(colours);
  auto actor = actorFor(data, line_colour, true);
  actor->GetProperty()->SetLineWidth(static_cast<float>(line_width_px * ratio));
  return actor;
}

vtkSmartPointer<vtkActor> makeGripAxesActor(const std::vector<core::GripPoint>& grips,
                                            double length_mm, double ratio,
                                            const Eigen::Matrix3d& R) {
  auto points = vtkSmartPointer<vtkPoints>::New();
  auto lines = vtkSmartPointer<vtkCellArray>::New();
  auto colours = vtkSmartPointer<vtkUnsignedCharArray>::New();
  colours->SetNumberOfComponents(3);
  const unsigned char axis_rgb[3][3] = {{235, 60, 60}, {60, 220, 60}, {70, 110, 255}};
  for (const core::GripPoint& g : grips) {
    const Eigen::Matrix3d frame =
        g.approach ? core::grasp::toolPose(Eigen::Isometry3d::Identity(),
                                           {g.name, g.position_mm, *g.approach, g.closing_axis})
                         .linear()
                   : R;
    for (int axis = 0; axis < 3; ++axis) {
      const Eigen::Vector3d end = g.position_mm + frame.col(axis) * length_mm;
      lines->InsertNextCell(2);
      lines->InsertCellPoint(points->InsertNextPoint(g.position_mm.data()));
      lines->InsertCellPoint(points->InsertNextPoint(end.data()));
      colours->InsertNextTypedTuple(axis_rgb[axis]);
    }
  }
  auto data = vtkSmartPointer<vtkPolyData>::New();
  data->SetPoints(points);
  data->SetLines(lines);
  data->GetCellData()->SetScalars(colours);
  auto actor = actorFor(data, Qt::white, true);
  actor->GetProperty()->SetLineWidth(static_cast<float>(4.0 * ratio));
  return actor;
}

vtkSmartPointer<vtkActor> makeGripMarkersActor(const std::vector<core::GripPoint>& grips,
                                               const QColor& colour, double size_px, double ratio) {
  std::vector<Eigen::Vector3f> points;
  for (const core::GripPoint& g : grips)
    points.push_back(g.position_mm.cast<float>());
  auto actor = makePointsActor(points, colour, size_px, ratio);
  actor->GetProperty()->SetRenderPointsAsSpheres(true);
  // Shaded spheres read as markers, not as more scan points.
  actor->GetProperty()->LightingOn();
  actor->GetProperty()->SetAmbient(0.3);
  actor->GetProperty()->SetDiffuse(0.8);
  return actor;
}

vtkSmartPointer<vtkProp> makeLabelActor(const QString& text, const Eigen::Vector3d& position_mm,
                                        const QColor& colour, int font_px, double ratio) {
  // A 2D text anchored at a 3D point: drawn over the scene, never hidden behind its points.
  auto label = vtkSmartPointer<vtkTextActor>::New();
  label->SetInput(text.toUtf8().constData());
  label->GetPositionCoordinate()->SetCoordinateSystemToWorld();
  label->GetPositionCoordinate()->SetValue(position_mm.x(), position_mm.y(), position_mm.z());
  vtkTextProperty* style = label->GetTextProperty();
  style->SetFontSize(static_cast<int>(font_px * ratio));
  style->SetColor(colour.redF(), colour.greenF(), colour.blueF());
  style->BoldOn();
  style->SetJustificationToCentered();
  style->SetVerticalJustificationToCentered();
  style->SetBackgroundColor(0.05, 0.05, 0.08);
  style->SetBackgroundOpacity(0.8);
  style->SetFrame(true);
  style->SetFrameColor(colour.redF(), colour.greenF(), colour.blueF());
  style->SetFrameWidth(std::max(1, static_cast<int>(ratio)));
  return label;
}

QColor detectionColour(int index) {
  const core::Rgb8 c = core::detectionColour(static_cast<std::size_t>(std::max(0, index)));
  return {c[0], c[1], c[2]};
}

} // namespace scanpick::ui
