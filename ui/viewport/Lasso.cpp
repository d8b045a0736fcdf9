#include "ui/viewport/Lasso.h"

#include <QMouseEvent>
#include <QPainter>
#include <vtkCamera.h>
#include <vtkMatrix4x4.h>
#include <vtkRenderer.h>

namespace scanpick::ui {

ScreenProjection ScreenProjection::fromRenderer(vtkRenderer* renderer, double width_px,
                                                double height_px) {
  ScreenProjection p;
  p.width_px = width_px;
  p.height_px = height_px;
  const double aspect = height_px > 0 ? width_px / height_px : 1.0;
  vtkMatrix4x4* m =
      renderer->GetActiveCamera()->GetCompositeProjectionTransformMatrix(aspect, -1, 1);
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      p.world_to_ndc(r, c) = m->GetElement(r, c);
  return p;
}

bool ScreenProjection::project(const Eigen::Vector3f& p_mm, QPointF& out_px) const {
  const Eigen::Vector4d h = world_to_ndc * Eigen::Vector4d(p_mm.x(), p_mm.y(), p_mm.z(), 1.0);
  if (h.w() <= 0)
    return false;
  const Eigen::Vector3d ndc = h.head<3>() / h.w();
  if (ndc.z() < -1 || ndc.z() > 1)
    return false;
  // NDC y points up; widget y points down.
  out_px = QPointF((ndc.x() + 1) * 0.5 * width_px, (1 - ndc.y()) * 0.5 * height_px);
  return true;
}

core::PointCloud selectInLasso(const core::PointCloud& cloud_mm, const ScreenProjection& projection,
                               const QPolygonF& polygon_px) {
  const QRectF bounds = polygon_px.boundingRect();
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < cloud_mm.size(); ++i) {
    const Eigen::Vector3f& p = cloud_mm.points_mm[i];
    QPointF s;
    if (core::isValid(p) && projection.project(p, s) && bounds.contains(s) &&
        polygon_px.containsPoint(s, Qt::OddEvenFill))
      kept.push_back(i);
  }
  core::PointCloud out;
  const auto take = [&kept](const auto& from, auto& to) {
    if (from.empty())
      return;
    to.reserve(kept.size());
    for (const std::size_t i : kept)
      to.push_back(from[i]);
  };
  take(cloud_mm.points_mm, out.points_mm);
  take(cloud_mm.normals, out.normals);
  take(cloud_mm.colors, out.colors);
  take(cloud_mm.intensity, out.intensity);
  take(cloud_mm.confidence, out.confidence);
  out.width = static_cast<std::uint32_t>(out.points_mm.size());
  out.height = 1;
  return out;
}

LassoOverlay::LassoOverlay(QWidget* viewport, std::function<void(const QPolygonF&)> on_finished)
    : QWidget(viewport), m_viewport(viewport), m_on_finished(std::move(on_finished)) {
  setObjectName(QStringLiteral("lassoOverlay"));
  // The overlay only paints; the viewport keeps receiving the events (filtered here).
  setAttribute(Qt::WA_TransparentForMouseEvents);
  setAttribute(Qt::WA_NoSystemBackground);
  viewport->installEventFilter(this);
  hide();
}

void LassoOverlay::setActive(bool active) {
  m_active = active;
  m_drawing = false;
  m_polygon.clear();
  setGeometry(m_viewport->rect());
  setVisible(active);
  m_viewport->setCursor(active ? Qt::CrossCursor : Qt::ArrowCursor);
  update();
}

bool LassoOverlay::eventFilter(QObject* watched, QEvent* event) {
  if (watched != m_viewport)
    return false;
  if (event->type() == QEvent::Resize)
    setGeometry(m_viewport->rect());
  if (!m_active)
    return false;
  switch (event->type()) {
  case QEvent::MouseButtonPress: {
    const auto* e = static_cast<QMouseEvent*>(event);
    if (e->button() != Qt::LeftButton)
      return false;
    m_drawing = true;
    m_polygon = QPolygonF{e->position()};
    update();
    return true;
  }
  case QEvent::MouseMove: {
    if (!m_drawing)
      return false;
    const QPointF p = static_cast<QMouseEvent*>(event)->position();
    // A corner every few pixels keeps the polygon small and the inside test fast.
    if (QLineF(m_polygon.back(), p).length() >= 3.0) {
      m_polygon << p;
      update();
    }
    return true;
  }
  case QEvent::MouseButtonRelease: {
    const auto* e = static_cast<QMouseEvent*>(event);
    if (!m_drawing || e->button() != Qt::LeftButton)
      return false;
    m_drawing = false;
    m_polygon << e->position();
    const QPolygonF polygon = m_polygon;
    m_polygon.clear();
    update();
    m_on_finished(polygon);
    return true;
  }
  case QEvent::MouseButtonDblClick:
    return true;
  default:
    return false;
  }
}

void LassoOverlay::paintEvent(QPaintEvent*) {
  if (m_polygon.size() < 2)
    return;
  QPainter painter(this);
  painter.setRenderHint(QPainter::Antialiasing);
  painter.setPen(QPen(QColor(255, 255, 0), 1.5, Qt::DashLine));
  painter.setBrush(QColor(255, 255, 0, 40));
  painter.drawPolygon(m_polygon);
}

} // namespace scanpick::ui
