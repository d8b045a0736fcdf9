#include "ui/viewport/Presenters.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vtkActor.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
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

/// Two unit vectors spanning the plane normal to `n`.
void planeBasis(const Eigen::Vector3d& n, Eigen::Vector3d& u, Eigen::Vector3d& v) {
  const Eigen::Vector3d helper =
      std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  u = n.cross(helper).normalized();
  v = n.cross(u).normalized();
}

} // namespace

vtkSmartPointer<vtkActor> makeCloudActor(const core::PointCloud& cloud, const QColor& colour,
                                         double point_size_px, double ratio, bool by_depth,
                                         const Eigen::Isometry3d& T) {
  auto points = vtkSmartPointer<vtkPoints>::New();
  auto verts = vtkSmartPointer<vtkCellArray>::New();
  auto colours = vtkSmartPointer<vtkUnsignedCharArray>::New();
  colours->SetNumberOfComponents(3);
  points->Allocate(static_cast<vtkIdType>(cloud.size()));
  float z_min = 0, z_max = 1;
  if (by_depth) {
    const Eigen::AlignedBox3f box = core::boundingBox(cloud);
    if (!box.isEmpty()) {
      z_min = box.min().z();
      z_max = std::max(box.max().z(), z_min + 1e-3f);
    }
  }
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3f& p = cloud.points_mm[i];
    if (!core::isValid(p))
      continue;
    const Eigen::Vector3d q = map(T, p);
    verts->InsertNextCell(1);
    verts->InsertCellPoint(points->InsertNextPoint(q.x(), q.y(), q.z()));
    if (by_depth) {
      // Near (small z) is amber, far is blue: reads as depth from the camera's view.
      const float t = std::clamp((p.z() - z_min) / (z_max - z_min), 0.0f, 1.0f);
      const unsigned char rgb[3] = {static_cast<unsigned char>(230 - 170 * t),
                                    static_cast<unsigned char>(170 - 40 * t),
                                    static_cast<unsigned char>(60 + 170 * t)};
      colours->InsertNextTypedTuple(rgb);
    }
  }
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
                        false, T);
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
    for (int axis = 0; axis < 3; ++axis) {
      const Eigen::Vector3d end = g.position_mm + R.col(axis) * length_mm;
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
  actor->GetProperty()->SetLineWidth(static_cast<float>(3.0 * ratio));
  return actor;
}

QColor detectionColour(int index) {
  // Golden-ratio hue steps keep neighbouring indices far apart on the colour wheel.
  const double hue = std::fmod(0.08 + index * 0.618033988749895, 1.0);
  return QColor::fromHsvF(static_cast<float>(hue), 0.85f, 1.0f);
}

} // namespace scanpick::ui
