#pragma once
/// @file DepthView.h
/// The scan's depth image with the result over it (View → Depth image): for an organized scan,
/// one pixel per cell, shaded by depth (near light, far dark), each detection's visible points in
/// its results-table colour with its ID at their middle, and its grip points as markers — the
/// same overlay as the 3D viewport. The image comes from core::renderDepthOverlay, computed in
/// the background (MainWindow); this widget only shows it, scaled to fit with its aspect kept.
/// For an unorganized scan, or no scan, it says why it is empty.

#include "core/output/DepthOverlay.h"

#include <QColor>
#include <QImage>
#include <QWidget>
#include <vector>

namespace scanpick::ui {

class DepthView : public QWidget {
  Q_OBJECT
public:
  /// What the view shows.
  enum class State {
    NoScan,      ///< nothing opened yet
    Unorganized, ///< the scan has no grid: no depth image
    Rendering,   ///< the image is being computed
    Image,       ///< image() is shown
  };

  explicit DepthView(QWidget* parent = nullptr);

  /// Shows `overlay` (its detection i labelled i + 1 in `colours[i]`, cycling).
  void setOverlay(const core::DepthOverlay& overlay, const std::vector<QColor>& colours);
  /// Shows no image, saying why (`state` other than Image).
  void setState(State state);
  /// Highlights detection `index` (-1: all alike), as the results table's selection does.
  void setSelected(int index);

  [[nodiscard]] State state() const { return m_state; }
  /// The depth image shown, one pixel per scan cell (null unless state() is Image).
  [[nodiscard]] const QImage& image() const { return m_image; }
  /// The overlay's marks (ID and grip pixels), one per detection.
  [[nodiscard]] const std::vector<core::DepthOverlayMark>& marks() const { return m_marks; }
  /// The sentence shown instead of an image, in the current language (empty with an image).
  [[nodiscard]] QString message() const;

  [[nodiscard]] QSize sizeHint() const override { return {320, 240}; }
  [[nodiscard]] QSize minimumSizeHint() const override { return {120, 90}; }

protected:
  void paintEvent(QPaintEvent* event) override;
  void changeEvent(QEvent* event) override;

private:
  /// Where the image is drawn in the widget (scaled to fit, centred).
  [[nodiscard]] QRectF imageRect() const;

  State m_state = State::NoScan;
  QImage m_image;
  std::vector<core::DepthOverlayMark> m_marks;
  std::vector<QColor> m_colours;
  int m_selected = -1;
};

} // namespace scanpick::ui
