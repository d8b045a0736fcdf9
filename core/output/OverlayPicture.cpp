#include "core/output/OverlayPicture.h"

#include "core/common/AtomicFile.h"
#include "core/common/Error.h"
#include "core/common/Rounding.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace scanpick::core {
namespace {

/// The dark of the ID boxes and of the grip markers' outline: darker than any depth shade and than
/// kNoDepthColour, so that both stand out on every background.
constexpr Rgb8 kMarkDark{8, 8, 12};
constexpr Rgb8 kMarkLight{255, 255, 255};

cv::Scalar scalar(const Rgb8& c) {
  return {double(c[0]), double(c[1]), double(c[2])};
}

/// The orthographic projection along +z fitted to the valid points' x-y extent.
PictureProjection orthographicFor(const PointCloud& scene, int fallback_width_px) {
  const Eigen::AlignedBox3f box = boundingBox(scene);
  if (box.isEmpty())
    throw Error("nothing to draw: the scene has no valid point");
  PictureProjection p;
  p.border_px = 4;
  p.width = std::max(16, fallback_width_px);
  const Eigen::Vector2d size = box.sizes().head<2>().cast<double>().cwiseMax(1e-3);
  const int inner_w = p.width - 2 * p.border_px - 1;
  const int max_inner_h = 4 * p.width - 2 * p.border_px - 1;
  p.px_per_mm = std::min(inner_w / size.x(), max_inner_h / size.y());
  p.height = std::max(16, int(std::ceil(size.y() * p.px_per_mm)) + 2 * p.border_px + 1);
  p.origin_mm = box.min().head<2>().cast<double>();
  return p;
}

/// Each point into the cell it projects to and, for `radius` > 0, the cells within `radius` of
/// it, the nearest point (smallest z) winning each cell; `filled` counts the cells that got one.
PointCloud projectNearest(const PointCloud& scene, const PictureProjection& projection, int radius,
                          std::size_t& filled) {
  PointCloud grid;
  grid.width = std::uint32_t(projection.width);
  grid.height = std::uint32_t(projection.height);
  grid.points_mm.assign(std::size_t(grid.width) * grid.height, invalidPoint());
  filled = 0;
  for (const Eigen::Vector3f& p : scene.points_mm) {
    if (!isValid(p))
      continue;
    const auto px = projection.pixelOf(p.cast<double>());
    if (!px)
      continue;
    for (int dr = -radius; dr <= radius; ++dr)
      for (int dc = -radius; dc <= radius; ++dc) {
        const int r = px->y() + dr, c = px->x() + dc;
        if (dr * dr + dc * dc > radius * radius || r < 0 || c < 0 || r >= int(grid.height) ||
            c >= int(grid.width))
          continue;
        Eigen::Vector3f& cell = grid.points_mm[std::size_t(r) * grid.width + std::size_t(c)];
        if (!isValid(cell))
          ++filled;
        if (!isValid(cell) || p.z() < cell.z())
          cell = p;
      }
  }
  return grid;
}

/// The splat radius (pixels) that closes the gaps between the `filled` cells of `grid`, from their
/// mean spacing in their bounding rectangle: a cell amid filled cells `spacing` apart is at most
/// half their diagonal from one of them. None below a spacing of 1.5 pixels, at most 4.
int splatRadius(const PointCloud& grid, std::size_t filled) {
  const int w = int(grid.width), h = int(grid.height);
  int min_c = w, max_c = -1, min_r = h, max_r = -1;
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c)
      if (isValid(grid.points_mm[std::size_t(r) * w + c])) {
        min_c = std::min(min_c, c);
        max_c = std::max(max_c, c);
        min_r = std::min(min_r, r);
        max_r = std::max(max_r, r);
      }
  if (filled == 0 || max_c < 0)
    return 0;
  const double area = double(max_c - min_c + 1) * double(max_r - min_r + 1);
  const double spacing = std::sqrt(area / double(filled));
  return spacing < 1.5 ? 0 : std::min(4, int(std::ceil(spacing * 0.7072)));
}

Eigen::Vector2d pixelOrNone(const PictureProjection& projection, const Eigen::Vector3d& p_mm) {
  const auto px = projection.pixelOf(p_mm);
  return px ? Eigen::Vector2d(px->cast<double>()) : Eigen::Vector2d(-1, -1);
}

bool onPicture(const Eigen::Vector2d& px) {
  return px.x() >= 0 && px.y() >= 0;
}

/// The grip markers and the IDs over the depth image (`image` wraps overlay.rgb, RGB order).
void drawMarks(cv::Mat& image, const std::vector<DepthOverlayMark>& marks,
               const std::vector<Rgb8>& colours) {
  const int text_px = std::clamp(int(std::lround(std::min(image.cols, image.rows) / 30.0)), 12, 64);
  const int stroke = std::max(2, text_px / 8);
  const int font = cv::FONT_HERSHEY_SIMPLEX;
  const double font_scale = cv::getFontScaleFromHeight(font, text_px, stroke);
  // Grip markers: a disc in the detection's colour, a white ring and a dark outline, so that it
  // stands out on the detection's own tint and on light and dark depths alike.
  const int grip_radius = std::max(6, text_px / 2);
  const int ring = std::max(2, grip_radius / 3);
  const int outline = std::max(2, grip_radius / 4);
  for (std::size_t k = 0; k < marks.size(); ++k)
    for (const Eigen::Vector2d& g : marks[k].grips_px) {
      if (!onPicture(g))
        continue;
      const cv::Point at(int(g.x()), int(g.y()));
      cv::circle(image, at, grip_radius + outline, scalar(kMarkDark), cv::FILLED, cv::LINE_AA);
      cv::circle(image, at, grip_radius, scalar(kMarkLight), cv::FILLED, cv::LINE_AA);
      cv::circle(image, at, grip_radius - ring, scalar(colours[k % colours.size()]), cv::FILLED,
                 cv::LINE_AA);
    }
  const int pad = std::max(3, text_px / 4);
  const int frame = std::max(1, text_px / 12);
  for (std::size_t k = 0; k < marks.size(); ++k) {
    if (!onPicture(marks[k].label_px))
      continue;
    const std::string text = std::to_string(k + 1);
    int baseline = 0;
    const cv::Size size = cv::getTextSize(text, font, font_scale, stroke, &baseline);
    const cv::Size box_size(size.width + 2 * pad, size.height + 2 * pad);
    // Centred on the label pixel, moved inside the picture where it would cross an edge.
    const int x = std::clamp(int(marks[k].label_px.x()) - box_size.width / 2, 0,
                             std::max(0, image.cols - box_size.width));
    const int y = std::clamp(int(marks[k].label_px.y()) - box_size.height / 2, 0,
                             std::max(0, image.rows - box_size.height));
    const cv::Rect box(x, y, box_size.width, box_size.height);
    const cv::Scalar colour = scalar(colours[k % colours.size()]);
    cv::rectangle(image, box, scalar(kMarkDark), cv::FILLED);
    cv::rectangle(image, box, colour, frame);
    cv::putText(image, text, cv::Point(x + pad, y + pad + size.height), font, font_scale, colour,
                stroke, cv::LINE_AA);
  }
}

void drawOn(DepthOverlay& overlay, const std::vector<Rgb8>& colours) {
  if (overlay.width <= 0 || overlay.height <= 0)
    return;
  try {
    cv::Mat image(overlay.height, overlay.width, CV_8UC3, overlay.rgb.data());
    drawMarks(image, overlay.marks, colours);
  } catch (const cv::Exception& e) {
    throw Error(std::string("cannot draw the picture's marks: ") + e.what());
  }
}

} // namespace

std::optional<Eigen::Vector2i> PictureProjection::pixelOf(const Eigen::Vector3d& p_mm) const {
  std::optional<Eigen::Vector2i> px;
  if (pinhole) {
    px = sensor.pixelOf(p_mm.cast<float>());
  } else if (p_mm.allFinite()) {
    const Eigen::Vector2d uv = (p_mm.head<2>() - origin_mm) * px_per_mm;
    px = Eigen::Vector2i(int(roundHalfAway(std::clamp(uv.x(), -1e6, 1e6))) + border_px,
                         int(roundHalfAway(std::clamp(uv.y(), -1e6, 1e6))) + border_px);
  }
  if (px && (px->x() < 0 || px->y() < 0 || px->x() >= width || px->y() >= height))
    px.reset();
  return px;
}

PictureScan organizeForPicture(const PointCloud& scene, const SensorModel& sensor,
                               int fallback_width_px) {
  if (scene.isOrganized())
    return {scene, std::nullopt};
  if (!scene.hasValidPoint())
    throw Error("nothing to draw: the scene has no valid point");
  std::size_t filled = 0;
  PictureScan out;
  if (sensor.fx > 0 && sensor.fy > 0 && sensor.width > 0 && sensor.height > 0) {
    PictureProjection pinhole;
    pinhole.pinhole = true;
    pinhole.sensor = sensor;
    pinhole.width = sensor.width;
    pinhole.height = sensor.height;
    out.scan_mm = projectNearest(scene, pinhole, 0, filled);
    out.projection = pinhole;
  }
  // Points that the sensor's camera does not see (another sensor's frame) get the fitted view.
  if (filled == 0) {
    out.projection = orthographicFor(scene, fallback_width_px);
    out.scan_mm = projectNearest(scene, *out.projection, 0, filled);
  }
  // Sparse points are drawn as discs, so that surfaces show as surfaces and a near one hides what
  // lies behind it.
  if (const int radius = splatRadius(out.scan_mm, filled); radius > 0)
    out.scan_mm = projectNearest(scene, *out.projection, radius, filled);
  return out;
}

DepthOverlay renderOverlayPicture(const PointCloud& scene_mm,
                                  const std::vector<const PointCloud*>& model_clouds_mm,
                                  const std::vector<Detection>& detections,
                                  const SensorModel& sensor, double tolerance_mm,
                                  int fallback_width_px) {
  const std::vector<Rgb8> colours = detectionColours(std::max<std::size_t>(1, detections.size()));
  if (scene_mm.isOrganized()) {
    DepthOverlay overlay =
        renderDepthOverlay(scene_mm, model_clouds_mm, detections, colours, tolerance_mm);
    drawOn(overlay, colours);
    return overlay;
  }
  const PictureScan picture = organizeForPicture(scene_mm, sensor, fallback_width_px);
  DepthOverlay overlay =
      renderDepthOverlay(picture.scan_mm, model_clouds_mm, detections, colours, tolerance_mm);
  // renderDepthOverlay finds pixels by direction from the camera at the origin, which only a
  // sensor's own grid guarantees; a projected grid maps points by its projection.
  if (picture.projection)
    for (std::size_t k = 0; k < detections.size(); ++k) {
      DepthOverlayMark& mark = overlay.marks[k];
      if (mark.pixels == 0)
        mark.label_px = pixelOrNone(*picture.projection, detections[k].centre_mm);
      for (std::size_t g = 0; g < mark.grips_px.size(); ++g)
        mark.grips_px[g] =
            pixelOrNone(*picture.projection, detections[k].grip_points_scene[g].position_mm);
    }
  drawOn(overlay, colours);
  return overlay;
}

void writeOverlayPng(const std::filesystem::path& path, const PointCloud& scene_mm,
                     const std::vector<const PointCloud*>& model_clouds_mm,
                     const std::vector<Detection>& detections, const SensorModel& sensor,
                     double tolerance_mm, int fallback_width_px) {
  checkWritable(path);
  DepthOverlay overlay = renderOverlayPicture(scene_mm, model_clouds_mm, detections, sensor,
                                              tolerance_mm, fallback_width_px);
  std::vector<std::uint8_t> png;
  try {
    const cv::Mat rgb(overlay.height, overlay.width, CV_8UC3, overlay.rgb.data());
    cv::Mat bgr;
    cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
    if (!cv::imencode(".png", bgr, png))
      throw Error(std::string("cannot encode the picture for ") + path.string());
  } catch (const cv::Exception& e) {
    throw Error(std::string("cannot encode the picture for ") + path.string() + ": " + e.what());
  }
  writeFileAtomic(path, std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
}

} // namespace scanpick::core
