#pragma once
/// @file Lasso.h
/// The screen-space lasso of the teach workflow: an overlay on the viewport that records a
/// polygon while the left button is dragged, and the projection that decides which points fall
/// inside it. The overlay lives on the GUI thread; the selection itself (selectInLasso) is a
/// plain function meant for a background job.

#include "core/cloud/PointCloud.h"

#include <Eigen/Core>
#include <QPolygonF>
#include <QWidget>
#include <functional>

class vtkRenderer;

namespace scanpick::ui {

/// World (mm) → viewport widget coordinates (logical pixels, y down) of one camera, captured
/// once on the GUI thread so points can be projected on any thread.
struct ScreenProjection {
  Eigen::Matrix4d world_to_ndc = Eigen::Matrix4d::Identity(); ///< VTK's composite projection
  double width_px = 0, height_px = 0;                         ///< widget size, logical pixels

  /// The renderer's current camera for a widget of `width_px` × `height_px` logical pixels.
  static ScreenProjection fromRenderer(vtkRenderer* renderer, double width_px, double height_px);
  /// Where `p_mm` appears; false when it lies behind the camera or outside the depth range.
  bool project(const Eigen::Vector3f& p_mm, QPointF& out_px) const;
};

/// The valid points of `cloud_mm` whose projection falls inside `polygon_px` (odd-even rule),
/// as an unorganized cloud with every channel carried along. Deterministic; no Qt GUI calls.
core::PointCloud selectInLasso(const core::PointCloud& cloud_mm, const ScreenProjection& projection,
                               const QPolygonF& polygon_px);

/// A transparent child of the viewport that, while active, takes the viewport's left-button
/// drags (so the camera stays still), draws the polygon and calls `on_finished` with it on
/// release. Other buttons and the wheel still reach the viewport.
class LassoOverlay : public QWidget {
  Q_OBJECT
public:
  LassoOverlay(QWidget* viewport, std::function<void(const QPolygonF&)> on_finished);
  void setActive(bool active);

protected:
  bool eventFilter(QObject* watched, QEvent* event) override;
  void paintEvent(QPaintEvent* event) override;

private:
  QWidget* m_viewport;
  std::function<void(const QPolygonF&)> m_on_finished;
  QPolygonF m_polygon;
  bool m_active = false;
  bool m_drawing = false;
};

} // namespace scanpick::ui
