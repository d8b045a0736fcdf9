#include "ui/panels/DepthView.h"

#include <QEvent>
#include <QPainter>
#include <QPainterPath>
#include <cstring>

namespace scanpick::ui {

DepthView::DepthView(QWidget* parent) : QWidget(parent) {
  setObjectName(QStringLiteral("depthView"));
  setAutoFillBackground(true);
  QPalette dark = palette();
  dark.setColor(QPalette::Window,
                QColor(core::kNoDepthColour[0], core::kNoDepthColour[1], core::kNoDepthColour[2]));
  dark.setColor(QPalette::WindowText, QColor(220, 220, 220));
  setPalette(dark);
}

void DepthView::setOverlay(const core::DepthOverlay& overlay, const std::vector<QColor>& colours) {
  QImage image(overlay.width, overlay.height, QImage::Format_RGB888);
  for (int row = 0; row < overlay.height; ++row)
    std::memcpy(image.scanLine(row), &overlay.rgb[std::size_t(row) * std::size_t(overlay.width)],
                std::size_t(overlay.width) * 3);
  m_image = std::move(image);
  m_marks = overlay.marks;
  m_colours = colours;
  m_selected = -1;
  m_state = State::Image;
  update();
}

void DepthView::setState(State state) {
  m_state = state;
  if (state != State::Image) {
    m_image = QImage();
    m_marks.clear();
  }
  update();
}

void DepthView::setSelected(int index) {
  m_selected = index;
  update();
}

QString DepthView::message() const {
  switch (m_state) {
  case State::NoScan:
    return tr("Open or capture a scan to see its depth image.");
  case State::Unorganized:
    return tr("No depth image: this scan is a list of points without the sensor's grid (an "
              "unorganized cloud). Scans saved by a PhoXi or a Kinect keep the grid; clouds that "
              "were filtered, merged or converted from a mesh lose it.");
  case State::Rendering:
    return tr("Drawing the depth image…");
  case State::Image:
    break;
  }
  return {};
}

QRectF DepthView::imageRect() const {
  if (m_image.isNull())
    return {};
  const QSizeF fitted = QSizeF(m_image.size()).scaled(QSizeF(size()), Qt::KeepAspectRatio);
  return {QPointF((width() - fitted.width()) / 2, (height() - fitted.height()) / 2), fitted};
}

void DepthView::paintEvent(QPaintEvent*) {
  QPainter painter(this);
  if (m_state != State::Image || m_image.isNull()) {
    painter.setPen(palette().color(QPalette::WindowText));
    painter.drawText(rect().adjusted(12, 12, -12, -12), Qt::AlignCenter | Qt::TextWordWrap,
                     message());
    return;
  }
  const QRectF target = imageRect();
  painter.setRenderHint(QPainter::SmoothPixmapTransform);
  painter.drawImage(target, m_image);
  painter.setRenderHint(QPainter::Antialiasing);
  const double scale = target.width() / m_image.width();
  const auto toWidget = [&](const Eigen::Vector2d& px) {
    return target.topLeft() + QPointF((px.x() + 0.5) * scale, (px.y() + 0.5) * scale);
  };
  const auto inside = [&](const Eigen::Vector2d& px) { return px.x() >= 0 && px.y() >= 0; };
  // Grip points: white rings with a dark edge, visible on light and dark depths alike.
  for (std::size_t k = 0; k < m_marks.size(); ++k) {
    const bool dim = m_selected >= 0 && m_selected != int(k);
    for (const Eigen::Vector2d& g : m_marks[k].grips_px) {
      if (!inside(g))
        continue;
      const QPointF at = toWidget(g);
      painter.setBrush(Qt::NoBrush);
      painter.setPen(QPen(QColor(0, 0, 0, dim ? 80 : 220), 4));
      painter.drawEllipse(at, 5.5, 5.5);
      painter.setPen(QPen(QColor(255, 255, 255, dim ? 90 : 255), 2));
      painter.drawEllipse(at, 5.5, 5.5);
    }
  }
  // IDs: the detection's number in its colour on a dark box framed in its colour, as in the 3D
  // view and the results table's row header.
  QFont font = painter.font();
  font.setBold(true);
  for (std::size_t k = 0; k < m_marks.size(); ++k) {
    if (!inside(m_marks[k].label_px))
      continue;
    const bool highlight = m_selected < 0 || m_selected == int(k);
    font.setPixelSize(highlight ? 15 : 11);
    painter.setFont(font);
    const QString text = QString::number(k + 1);
    const QColor colour = m_colours.empty() ? QColor(Qt::white) : m_colours[k % m_colours.size()];
    QRectF box = painter.fontMetrics().boundingRect(text).adjusted(-4, -1, 4, 1);
    box.moveCenter(toWidget(m_marks[k].label_px));
    painter.setPen(QPen(colour, 1.5));
    painter.setBrush(QColor(0, 0, 0, highlight ? 200 : 120));
    painter.drawRoundedRect(box, 3, 3);
    painter.setPen(colour);
    painter.drawText(box, Qt::AlignCenter, text);
  }
}

void DepthView::changeEvent(QEvent* event) {
  // The sentence shown without an image is made in paintEvent, in the language of the moment.
  if (event->type() == QEvent::LanguageChange)
    update();
  QWidget::changeEvent(event);
}

} // namespace scanpick::ui
