#include "ui/panels/CoverageSphere.h"

#include <QEvent>
#include <QPainter>
#include <algorithm>
#include <cmath>
#include <numbers>

namespace scanpick::ui {
namespace {

constexpr double kMargin = 20.0; // room for the axis labels around each disc

/// Where a direction of the upper (`upper`) or lower hemisphere lies on its disc, in disc units
/// (radius 1): Lambert's azimuthal equal-area map, the pole at the centre, the equator on the rim.
/// Seen from above +X points right; seen from below (mirrored) +X points left; +Y points up on
/// both.
QPointF discPoint(const Eigen::Vector3d& d, bool upper) {
  const double theta = std::acos(std::clamp(upper ? d.z() : -d.z(), -1.0, 1.0));
  const double n = std::numbers::sqrt2 * std::sin(theta / 2.0);
  const double h = std::hypot(d.x(), d.y());
  if (h < 1e-12)
    return {0, 0};
  return {(upper ? 1.0 : -1.0) * n * d.x() / h, -n * d.y() / h};
}

/// The direction drawn at disc point (u, v) (radius ≤ 1), the inverse of discPoint.
Eigen::Vector3d discDirection(double u, double v, bool upper) {
  const double n = std::min(1.0, std::hypot(u, v));
  const double theta = 2.0 * std::asin(n / std::numbers::sqrt2);
  const double s = n > 1e-12 ? std::sin(theta) / n : 0.0;
  return {s * (upper ? u : -u), -s * v, (upper ? 1.0 : -1.0) * std::cos(theta)};
}

} // namespace

CoverageSphere::CoverageSphere(QWidget* parent) : QWidget(parent) {
  setObjectName(QStringLiteral("coverageSphere"));
  setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Expanding);
}

void CoverageSphere::setCoverage(const core::ViewCoverage& coverage, double tolerance_deg) {
  m_coverage = coverage;
  m_reach = std::cos(tolerance_deg * std::numbers::pi / 180.0);
  m_cache = QImage();
  update();
}

void CoverageSphere::clear() {
  m_coverage.reset();
  m_cache = QImage();
  update();
}

bool CoverageSphere::covered(const Eigen::Vector3d& d_part) const {
  // As core::viewCoverage counts a direction: within the tolerance of a placed view.
  return std::any_of(m_coverage->view_directions_part.begin(),
                     m_coverage->view_directions_part.end(),
                     [&](const Eigen::Vector3d& v) { return v.dot(d_part) >= m_reach; });
}

CoverageSphere::Layout CoverageSphere::layout() const {
  // Side by side, a margin for the axis labels around each, centred, the captions below.
  const double caption = fontMetrics().height() + 6.0;
  Layout l;
  l.radius = std::max(
      10.0, std::min((width() - 5 * kMargin) / 4.0, (height() - 2 * kMargin - caption) / 2.0));
  const double y = (height() - caption) / 2.0;
  l.upper = {width() / 2.0 - 1.5 * kMargin - l.radius, y};
  l.lower = {width() / 2.0 + 1.5 * kMargin + l.radius, y};
  return l;
}

QPointF CoverageSphere::positionOf(const Eigen::Vector3d& d_part) const {
  const Layout l = layout();
  const bool upper = d_part.z() >= 0;
  return (upper ? l.upper : l.lower) + discPoint(d_part.normalized(), upper) * l.radius;
}

QImage CoverageSphere::discsImage(const Layout& l) const {
  QImage image(size(), QImage::Format_ARGB32_Premultiplied);
  image.fill(Qt::transparent);
  const QRgb in = coveredColour().rgb(), out = uncoveredColour().rgb(), none = qRgb(190, 190, 190);
  for (const bool upper : {true, false}) {
    const QPointF c = upper ? l.upper : l.lower;
    const int x0 = std::max(0, int(c.x() - l.radius)),
              x1 = std::min(width(), int(c.x() + l.radius) + 1);
    const int y0 = std::max(0, int(c.y() - l.radius)),
              y1 = std::min(height(), int(c.y() + l.radius) + 1);
    for (int y = y0; y < y1; ++y) {
      auto* line = reinterpret_cast<QRgb*>(image.scanLine(y));
      for (int x = x0; x < x1; ++x) {
        const double u = (x + 0.5 - c.x()) / l.radius, v = (y + 0.5 - c.y()) / l.radius;
        if (u * u + v * v > 1.0)
          continue;
        line[x] = !m_coverage ? none : covered(discDirection(u, v, upper)) ? in : out;
      }
    }
  }
  return image;
}

void CoverageSphere::paintEvent(QPaintEvent*) {
  const Layout l = layout();
  if (m_cache.size() != size())
    m_cache = discsImage(l);
  QPainter painter(this);
  painter.drawImage(0, 0, m_cache);
  painter.setRenderHint(QPainter::Antialiasing);
  const QColor text = palette().color(QPalette::WindowText);
  // Rims, axes and captions: which way each disc is seen.
  for (const bool upper : {true, false}) {
    const QPointF c = upper ? l.upper : l.lower;
    painter.setBrush(Qt::NoBrush);
    painter.setPen(QPen(QColor(80, 80, 80), 1.5));
    painter.drawEllipse(c, l.radius, l.radius);
    painter.setPen(QPen(QColor(0, 0, 0, 60), 1, Qt::DashLine));
    painter.drawLine(c - QPointF(l.radius, 0), c + QPointF(l.radius, 0));
    painter.drawLine(c - QPointF(0, l.radius), c + QPointF(0, l.radius));
    painter.setPen(text);
    const QPointF x_end = c + discPoint(Eigen::Vector3d::UnitX(), upper) * l.radius;
    const QPointF y_end = c + discPoint(Eigen::Vector3d::UnitY(), upper) * l.radius;
    painter.drawText(QRectF(x_end.x() + (upper ? 2 : -kMargin - 2), x_end.y() - 8, kMargin, 16),
                     Qt::AlignCenter, QStringLiteral("+X"));
    painter.drawText(QRectF(y_end.x() - kMargin / 2, y_end.y() - kMargin, kMargin, kMargin - 2),
                     Qt::AlignHCenter | Qt::AlignBottom, QStringLiteral("+Y"));
    const QString caption = upper ? tr("From above (+Z)") : tr("From below (−Z)");
    painter.drawText(QRectF(c.x() - l.radius - kMargin, c.y() + l.radius + 4,
                            2 * (l.radius + kMargin), fontMetrics().height() + 2),
                     Qt::AlignHCenter | Qt::AlignTop, caption);
  }
  if (!m_coverage)
    return;
  // Taught views: dark dots with a white ring, visible on both colours.
  for (const Eigen::Vector3d& d : m_coverage->view_directions_part) {
    painter.setPen(QPen(Qt::white, 2));
    painter.setBrush(viewColour());
    painter.drawEllipse(positionOf(d), 6, 6);
  }
  // Suggestions: white discs numbered in the order the panel lists them.
  QFont font = painter.font();
  font.setBold(true);
  font.setPixelSize(12);
  painter.setFont(font);
  for (std::size_t i = 0; i < m_coverage->missing_part.size(); ++i) {
    const QPointF at = positionOf(m_coverage->missing_part[i]);
    painter.setPen(QPen(Qt::black, 1.5));
    painter.setBrush(suggestionColour());
    painter.drawEllipse(at, 9, 9);
    painter.drawText(QRectF(at.x() - 9, at.y() - 9, 18, 18), Qt::AlignCenter,
                     QString::number(i + 1));
  }
}

void CoverageSphere::changeEvent(QEvent* event) {
  // The captions are made in paintEvent, in the language of the moment.
  if (event->type() == QEvent::LanguageChange)
    update();
  QWidget::changeEvent(event);
}

} // namespace scanpick::ui
