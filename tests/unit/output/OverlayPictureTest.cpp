#include "core/output/OverlayPicture.h"

#include "core/common/AtomicFile.h"
#include "core/common/Error.h"
#include "tests/support/TempDir.h"

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

using namespace scanpick;
using namespace scanpick::core;

namespace {

// A 320 x 240 camera (400 px focal length) looking at a floor 800 mm away with two square plates
// (40 mm, 20 mm above the floor) centred at x = ∓60 mm; at 780 mm a pixel spans 1.95 mm, so each
// plate covers about 20 x 20 pixels, centred 31 pixels left and right of the image centre. The top
// 24 rows (10 %) see a rim 700 mm away: the depth shading spans 700-800 mm, so a plate's tint keeps
// 0.8 of its detection's colour and only the drawn marks carry the colour itself.
constexpr int kWidth = 320, kHeight = 240, kRimRows = 24;
constexpr double kFocal = 400, kRimZ = 700, kPlateZ = 780, kFloorZ = 800;
constexpr double kHalfPlate = 20, kPlateX = 60;
constexpr double kTolerance_mm = 2.0;
// Each grip lies 50 mm below its plate's centre, on the floor: its marker stays clear of the ID
// box at the plate's centre.
constexpr double kGripY = 50;

SensorModel camera() {
  SensorModel s;
  s.preset = "custom";
  s.width = kWidth;
  s.height = kHeight;
  s.fx = s.fy = kFocal;
  s.cx = (kWidth - 1) / 2.0;
  s.cy = (kHeight - 1) / 2.0;
  return s;
}

bool onPlate(double x, double y) {
  return std::abs(y) <= kHalfPlate &&
         (std::abs(x - kPlateX) <= kHalfPlate || std::abs(x + kPlateX) <= kHalfPlate);
}

/// The scene as the camera's organized grid: each cell's ray meets a plate or the floor.
PointCloud organizedScene() {
  const SensorModel s = camera();
  PointCloud scan;
  scan.width = kWidth;
  scan.height = kHeight;
  for (int r = 0; r < kHeight; ++r)
    for (int c = 0; c < kWidth; ++c) {
      const double rx = (c - s.cx) / s.fx, ry = (r - s.cy) / s.fy;
      const double z = r < kRimRows                          ? kRimZ
                       : onPlate(rx * kPlateZ, ry * kPlateZ) ? kPlateZ
                                                             : kFloorZ;
      scan.points_mm.emplace_back(float(rx * z), float(ry * z), float(z));
    }
  return scan;
}

/// The plate model (model frame: centred, z = 0), sampled every 0.5 mm.
PointCloud plateModel() {
  std::vector<Eigen::Vector3f> points;
  for (double x = -kHalfPlate; x <= kHalfPlate; x += 0.5)
    for (double y = -kHalfPlate; y <= kHalfPlate; y += 0.5)
      points.emplace_back(float(x), float(y), 0.0f);
  return PointCloud::fromPoints(std::move(points));
}

/// Detection 0 on the left plate, detection 1 on the right one, each with one grip point.
std::vector<Detection> detections() {
  std::vector<Detection> out;
  for (const double x : {-kPlateX, kPlateX}) {
    Detection d;
    d.T_scene_model.translation() = Eigen::Vector3d(x, 0, kPlateZ);
    d.centre_mm = d.T_scene_model.translation();
    d.grip_points_scene.push_back({"below", Eigen::Vector3d(x, kGripY, kPlateZ)});
    out.push_back(d);
  }
  return out;
}

Rgb8 at(const cv::Mat& bgr, int col, int row) {
  const auto& p = bgr.at<cv::Vec3b>(row, col);
  return {p[2], p[1], p[0]};
}

bool near(const Rgb8& a, const Rgb8& b, int tolerance) {
  for (int i = 0; i < 3; ++i)
    if (std::abs(int(a[std::size_t(i)]) - int(b[std::size_t(i)])) > tolerance)
      return false;
  return true;
}

/// Pixels within `half` of `centre` (column, row) for which `test` holds.
template <typename Test>
int countAround(const cv::Mat& bgr, const Eigen::Vector2d& centre, int half, Test test) {
  int n = 0;
  for (int r = int(centre.y()) - half; r <= int(centre.y()) + half; ++r)
    for (int c = int(centre.x()) - half; c <= int(centre.x()) + half; ++c)
      if (r >= 0 && c >= 0 && r < bgr.rows && c < bgr.cols && test(at(bgr, c, r)))
        ++n;
  return n;
}

bool isMarkDark(const Rgb8& c) {
  // Darker than any depth shade (45 and up) and than kNoDepthColour's blue (40).
  return c[0] <= 16 && c[1] <= 16 && c[2] <= 20;
}
bool isWhite(const Rgb8& c) {
  // The depth shades stop at 240 and the detection colours are saturated.
  return c[0] >= 250 && c[1] >= 250 && c[2] >= 250;
}

/// Checks the PNG at `path` shows, for each detection k, a dark ID box holding pixels of its
/// colour (the frame and the digit) and none of the other detection's colour at its label pixel,
/// and its grip marker: its colour at the grip pixel, a white ring and a dark outline around.
void expectMarks(const std::filesystem::path& path, const DepthOverlay& picture) {
  const cv::Mat bgr = cv::imread(path.string(), cv::IMREAD_COLOR);
  ASSERT_FALSE(bgr.empty()) << path;
  ASSERT_EQ(bgr.cols, picture.width);
  ASSERT_EQ(bgr.rows, picture.height);
  ASSERT_EQ(picture.marks.size(), 2u);
  // IDs are about 1/30 of the smaller side high (at least 12 pixels): the box and its frame lie
  // within 1.5 of that and a few pixels of padding from the label pixel, the grip marker farther.
  const int text_px = std::max(12, int(std::lround(std::min(bgr.cols, bgr.rows) / 30.0)));
  const int box_half = text_px * 3 / 2 + 6;
  for (std::size_t k = 0; k < 2; ++k) {
    SCOPED_TRACE("detection " + std::to_string(k + 1));
    const Rgb8 mine = detectionColour(k), other = detectionColour(1 - k);
    const DepthOverlayMark& mark = picture.marks[k];
    // The box is at least 18 pixels across (12-pixel digits with 3 pixels of padding).
    EXPECT_GE(countAround(bgr, mark.label_px, box_half, isMarkDark), 60);
    EXPECT_GE(countAround(bgr, mark.label_px, 4, [&](const Rgb8& c) { return near(c, mine, 60); }),
              3)
        << "no digit of the ID in its colour";
    EXPECT_GE(countAround(bgr, mark.label_px, box_half, [&](const Rgb8& c) { return c == mine; }),
              10)
        << "no frame in its colour";
    EXPECT_EQ(countAround(bgr, mark.label_px, box_half,
                          [&](const Rgb8& c) { return near(c, other, 20); }),
              0);
    ASSERT_EQ(mark.grips_px.size(), 1u);
    const Eigen::Vector2d g = mark.grips_px[0];
    EXPECT_EQ(at(bgr, int(g.x()), int(g.y())), mine);
    // The marker is about as wide as the ID is high.
    EXPECT_GE(countAround(bgr, g, text_px, isWhite), 12) << "no white ring";
    EXPECT_GE(countAround(bgr, g, text_px, isMarkDark), 12) << "no dark outline";
  }
}

/// Where the camera sees a scene point (mm), rounded to the cell.
Eigen::Vector2d cameraPixel(const Eigen::Vector3d& p) {
  const SensorModel s = camera();
  return {std::round(s.fx * p.x() / p.z() + s.cx), std::round(s.fy * p.y() / p.z() + s.cy)};
}

PointCloud unorganized(const PointCloud& grid) {
  return PointCloud::fromPoints(grid.points_mm);
}

} // namespace

TEST(OverlayPicture, OrganizedScanIsItsDepthOverlayWithIdsAndGripMarkers) {
  const PointCloud scene = organizedScene();
  const PointCloud model = plateModel();
  const auto found = detections();
  test::TempDir dir;
  writeOverlayPng(dir / "p.png", scene, {&model}, found, camera(), kTolerance_mm);
  const DepthOverlay picture =
      renderOverlayPicture(scene, {&model}, found, camera(), kTolerance_mm);
  const DepthOverlay plain =
      renderDepthOverlay(scene, {&model}, found, detectionColours(2), kTolerance_mm);
  EXPECT_EQ(picture.width, kWidth);
  EXPECT_EQ(picture.height, kHeight);
  for (std::size_t k = 0; k < 2; ++k) {
    // The same marks as the GUI's depth view gets; the label on the plate's middle, the grip
    // where the camera sees it.
    EXPECT_EQ(picture.marks[k].label_px, plain.marks[k].label_px);
    EXPECT_EQ(picture.marks[k].grips_px, plain.marks[k].grips_px);
    EXPECT_GT(picture.marks[k].pixels, 300u); // about 20 x 20 cells on the plate
    EXPECT_LE((picture.marks[k].label_px - cameraPixel(found[k].centre_mm)).norm(), 1.5);
    EXPECT_LE(
        (picture.marks[k].grips_px[0] - cameraPixel(found[k].grip_points_scene[0].position_mm))
            .norm(),
        1.5);
  }
  // Away from the marks the picture is the depth overlay itself.
  EXPECT_EQ(picture.rgb[5], plain.rgb[5]);
  EXPECT_EQ(std::count_if(plain.rgb.begin(), plain.rgb.end(), isWhite), 0);
  expectMarks(dir / "p.png", picture);
}

TEST(OverlayPicture, UnorganizedScanIsProjectedThroughTheSensor) {
  // The same points without their grid: the sensor's camera puts each back into its cell.
  const PointCloud scene = unorganized(organizedScene());
  const PointCloud model = plateModel();
  const auto found = detections();
  test::TempDir dir;
  writeOverlayPng(dir / "p.png", scene, {&model}, found, camera(), kTolerance_mm);
  const DepthOverlay picture =
      renderOverlayPicture(scene, {&model}, found, camera(), kTolerance_mm);
  EXPECT_EQ(picture.width, kWidth);
  EXPECT_EQ(picture.height, kHeight);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_GT(picture.marks[k].pixels, 300u);
    EXPECT_LE((picture.marks[k].label_px - cameraPixel(found[k].centre_mm)).norm(), 1.5);
    EXPECT_EQ(picture.marks[k].grips_px[0], cameraPixel(found[k].grip_points_scene[0].position_mm));
  }
  expectMarks(dir / "p.png", picture);
}

TEST(OverlayPicture, UnorganizedScanWithoutIntrinsicsIsSeenAlongZ) {
  const PointCloud scene = unorganized(organizedScene());
  const PointCloud model = plateModel();
  const auto found = detections();
  // At 900 pixels wide the floor's points (about 2 mm apart) fall about 2.8 pixels apart: the gaps
  // between them must be filled.
  constexpr int kPictureWidth = 900;
  const PictureScan grid = organizeForPicture(scene, SensorModel{}, kPictureWidth);
  ASSERT_TRUE(grid.projection);
  EXPECT_FALSE(grid.projection->pinhole);
  const Eigen::AlignedBox3f box = boundingBox(scene);
  // Fitted to the x extent: 900 pixels less a 4-pixel border on each side and one for the last
  // cell; y follows at the same scale.
  const double scale = (kPictureWidth - 9) / double(box.sizes().x());
  EXPECT_NEAR(grid.projection->px_per_mm, scale, 1e-9);
  EXPECT_EQ(grid.scan_mm.width, std::uint32_t(kPictureWidth));
  EXPECT_EQ(grid.scan_mm.height, std::uint32_t(std::ceil(box.sizes().y() * scale)) + 9);
  const auto pixel = [&](const Eigen::Vector3d& p) {
    return Eigen::Vector2d(std::round((p.x() - box.min().x()) * scale) + 4,
                           std::round((p.y() - box.min().y()) * scale) + 4);
  };
  // The floor between the plates and below them leaves no cell empty. (Beside a plate's outer edge
  // lies a 2 mm strip of floor that the camera does not see: no data, left out here.)
  std::size_t empty_inside = 0, inside = 0;
  const auto countEmpty = [&](const Eigen::Vector3d& from_mm, const Eigen::Vector3d& to_mm) {
    const Eigen::Vector2d from = pixel(from_mm), to = pixel(to_mm);
    for (int r = int(from.y()); r <= int(to.y()); ++r)
      for (int c = int(from.x()); c <= int(to.x()); ++c, ++inside)
        if (!isValid(grid.scan_mm.points_mm[std::size_t(r) * grid.scan_mm.width + std::size_t(c)]))
          ++empty_inside;
  };
  countEmpty({-35, -100, kFloorZ}, {35, 100, kFloorZ});
  countEmpty({-150, 25, kFloorZ}, {150, 100, kFloorZ});
  EXPECT_EQ(empty_inside, 0u) << "of " << inside << " cells";

  test::TempDir dir;
  writeOverlayPng(dir / "p.png", scene, {&model}, found, SensorModel{}, kTolerance_mm,
                  kPictureWidth);
  const DepthOverlay picture =
      renderOverlayPicture(scene, {&model}, found, SensorModel{}, kTolerance_mm, kPictureWidth);
  EXPECT_EQ(picture.width, kPictureWidth);
  EXPECT_EQ(picture.height, int(grid.scan_mm.height));
  for (std::size_t k = 0; k < 2; ++k) {
    // A 40 mm plate is about 56 pixels across here; its points drawn as discs and the floor it
    // hides from the camera (a 2 mm strip along its outer side) move its middle by a pixel or two.
    EXPECT_GT(picture.marks[k].pixels, 2500u);
    EXPECT_LE((picture.marks[k].label_px - pixel(found[k].centre_mm)).norm(), 3.0);
    EXPECT_EQ(picture.marks[k].grips_px[0], pixel(found[k].grip_points_scene[0].position_mm));
  }
  expectMarks(dir / "p.png", picture);
}

TEST(OverlayPicture, FailedWritesLeaveNoFileAndKeepTheOldOne) {
  const PointCloud scene = organizedScene();
  const PointCloud model = plateModel();
  const auto found = detections();
  test::TempDir dir;
  EXPECT_THROW(
      writeOverlayPng(dir / "missing" / "p.png", scene, {&model}, found, camera(), kTolerance_mm),
      Error);
  EXPECT_FALSE(std::filesystem::exists(dir / "missing"));
  EXPECT_EQ(test::fileCount(dir.path()), 0u);
  // A picture that cannot be made (no valid point) does not replace the one already there.
  writeOverlayPng(dir / "p.png", scene, {&model}, found, camera(), kTolerance_mm);
  const std::string good = readFile(dir / "p.png");
  const PointCloud nothing = PointCloud::fromPoints({invalidPoint(), invalidPoint()});
  EXPECT_THROW(writeOverlayPng(dir / "p.png", nothing, {&model}, {}, SensorModel{}, kTolerance_mm),
               Error);
  EXPECT_EQ(readFile(dir / "p.png"), good);
  EXPECT_EQ(test::fileCount(dir.path()), 1u);
}

TEST(OverlayPicture, DetectionColoursAreDistinctAndSaturated) {
  // Hue steps of the golden ratio: the first colours differ clearly; saturation 0.85 at full value
  // puts the largest channel at 255 and the smallest at 38.
  const auto colours = detectionColours(8);
  for (std::size_t i = 0; i < colours.size(); ++i) {
    EXPECT_EQ(*std::max_element(colours[i].begin(), colours[i].end()), 255);
    EXPECT_EQ(*std::min_element(colours[i].begin(), colours[i].end()), 38);
    for (std::size_t j = 0; j < i; ++j)
      EXPECT_FALSE(near(colours[i], colours[j], 30)) << i << " vs " << j;
  }
}
