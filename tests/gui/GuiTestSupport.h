#pragma once
// Helpers of the GUI tests: screenshot checks and where screenshots are kept.
#include <QColor>
#include <QDir>
#include <QImage>
#include <QString>
#include <QWidget>
#include <cstdlib>
#include <set>

namespace scanpick::test {

/// Folder for the screenshots the GUI tests save (inside the build tree).
inline QString screenshotDir() {
  const QString dir = QStringLiteral(SCANPICK_BINARY_DIR "/gui-screenshots");
  QDir().mkpath(dir);
  return dir;
}

/// Pixels whose colour is within `tolerance` (per channel) of `colour`.
inline int countColour(const QImage& image, const QColor& colour, int tolerance = 40) {
  int n = 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const QRgb p = image.pixel(x, y);
      if (std::abs(qRed(p) - colour.red()) <= tolerance &&
          std::abs(qGreen(p) - colour.green()) <= tolerance &&
          std::abs(qBlue(p) - colour.blue()) <= tolerance)
        ++n;
    }
  return n;
}

/// Pixels of a neutral grey (channels within 4 of each other) between `lo` and `hi`: the
/// recognition view draws the scene in greys by depth.
inline int countGrey(const QImage& image, int lo = 60, int hi = 235) {
  int n = 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const QRgb p = image.pixel(x, y);
      if (std::abs(qRed(p) - qGreen(p)) <= 4 && std::abs(qGreen(p) - qBlue(p)) <= 4 &&
          qGreen(p) >= lo && qGreen(p) <= hi)
        ++n;
    }
  return n;
}

/// Distinct colours in a coarse (4-bit per channel) histogram: a blank or uniform frame has
/// very few, a rendered scene many.
inline int distinctColours(const QImage& image) {
  std::set<int> seen;
  for (int y = 0; y < image.height(); y += 2)
    for (int x = 0; x < image.width(); x += 2) {
      const QRgb p = image.pixel(x, y);
      seen.insert((qRed(p) >> 4) << 8 | (qGreen(p) >> 4) << 4 | (qBlue(p) >> 4));
    }
  return static_cast<int>(seen.size());
}

} // namespace scanpick::test

namespace scanpick::test {

/// Saves a picture of the whole `widget` (viewport included) for the user guide:
/// screenshotDir()/docs/<name>, at most 1000 px wide so it stays small (< 300 KB).
/// `./tests/gui/update-doc-images.sh` copies these into docs/images. Returns the grabbed image.
inline QImage saveDocImage(QWidget& widget, const QString& name) {
  QImage image = widget.grab().toImage();
  if (image.width() > 1000)
    image = image.scaledToWidth(1000, Qt::SmoothTransformation);
  const QString dir = screenshotDir() + QStringLiteral("/docs");
  QDir().mkpath(dir);
  image.convertToFormat(QImage::Format_RGB888).save(dir + "/" + name);
  return image;
}

} // namespace scanpick::test
