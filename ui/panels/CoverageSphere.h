#pragma once
/// @file CoverageSphere.h
/// The sphere of viewing directions of one part (part frame), coloured by how its taught views
/// cover it (View → View coverage): two discs, the upper half seen from above (+Z) and the lower
/// half seen from below (−Z), each a Lambert azimuthal equal-area map, so that a colour's share of
/// a disc's area is its share of the directions. Directions within the tolerance of a taught view
/// are drawn in coveredColour(), the others in uncoveredColour(); each taught view's direction is
/// a dot in viewColour(), each suggested direction a white disc numbered 1, 2, 3. Drawn with
/// QPainter (no OpenGL: robust under Xvfb and remote desktops). GUI thread only.

#include "core/model/ViewCoverage.h"

#include <Eigen/Core>
#include <QColor>
#include <QImage>
#include <QPointF>
#include <QWidget>
#include <optional>

namespace scanpick::ui {

class CoverageSphere : public QWidget {
  Q_OBJECT
public:
  explicit CoverageSphere(QWidget* parent = nullptr);

  /// Shows `coverage`, measured with `tolerance_deg` (ViewCoverageOptions::tolerance_deg).
  void setCoverage(const core::ViewCoverage& coverage, double tolerance_deg);
  /// Shows two empty grey discs.
  void clear();

  /// Where direction `d_part` (unit, part frame) is drawn, in widget coordinates (logical
  /// pixels): on the upper disc for d.z ≥ 0, on the lower one otherwise.
  [[nodiscard]] QPointF positionOf(const Eigen::Vector3d& d_part) const;

  static QColor coveredColour() { return {70, 150, 215}; }
  static QColor uncoveredColour() { return {235, 145, 50}; }
  static QColor viewColour() { return {25, 25, 25}; }
  static QColor suggestionColour() { return {255, 255, 255}; }

  [[nodiscard]] QSize sizeHint() const override { return {340, 200}; }
  [[nodiscard]] QSize minimumSizeHint() const override { return {180, 110}; }

protected:
  void paintEvent(QPaintEvent* event) override;
  void changeEvent(QEvent* event) override;

private:
  /// The two discs: centres and common radius (logical pixels).
  struct Layout {
    QPointF upper, lower;
    double radius = 0;
  };
  [[nodiscard]] Layout layout() const;
  /// The discs' pixels coloured by coverage (made again when the size or the coverage changes).
  [[nodiscard]] QImage discsImage(const Layout& l) const;
  [[nodiscard]] bool covered(const Eigen::Vector3d& d_part) const;

  std::optional<core::ViewCoverage> m_coverage;
  double m_reach = 0.5; // cosine of the tolerance
  mutable QImage m_cache;
};

} // namespace scanpick::ui
