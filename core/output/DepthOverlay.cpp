#include "core/output/DepthOverlay.h"

#include "core/common/Error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace scanpick::core {
namespace {

/// The posed model points of every detection, hashed by cells of `cell_mm`, so that the points
/// near a scan point are found by looking at its cell and the 26 around it.
class PosedModels {
public:
  explicit PosedModels(double cell_mm) : m_cell(cell_mm) {}

  void add(const Eigen::Vector3f& p, int detection) {
    m_points.push_back({p, detection});
    m_boxes.resize(std::max<std::size_t>(m_boxes.size(), std::size_t(detection) + 1));
    m_boxes[std::size_t(detection)].extend(p);
  }

  void index() {
    for (std::uint32_t i = 0; i < m_points.size(); ++i)
      m_cells[key(cellOf(m_points[i].p))].push_back(i);
    m_any.setEmpty();
    for (auto& box : m_boxes)
      if (!box.isEmpty()) {
        box.min().array() -= float(m_cell);
        box.max().array() += float(m_cell);
        m_any.extend(box);
      }
  }

  /// The detection with a posed model point nearest to `q` within the cell size, or -1.
  [[nodiscard]] int nearest(const Eigen::Vector3f& q) const {
    if (!m_any.contains(q))
      return -1;
    const Eigen::Vector3i c = cellOf(q);
    float best = float(m_cell * m_cell);
    int found = -1;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const auto it = m_cells.find(key(c + Eigen::Vector3i(dx, dy, dz)));
          if (it == m_cells.end())
            continue;
          for (const std::uint32_t i : it->second) {
            const float d2 = (m_points[i].p - q).squaredNorm();
            if (d2 <= best) {
              best = d2;
              found = m_points[i].detection;
            }
          }
        }
    return found;
  }

private:
  struct Posed {
    Eigen::Vector3f p;
    int detection;
  };
  [[nodiscard]] Eigen::Vector3i cellOf(const Eigen::Vector3f& p) const {
    return (p.cast<double>() / m_cell).array().floor().cast<int>();
  }
  static std::uint64_t key(const Eigen::Vector3i& c) {
    // 21 bits per axis: cells of a millimetre or more span ±1 km.
    const auto part = [](int v) { return std::uint64_t(std::uint32_t(v) & 0x1FFFFFu); };
    return part(c.x()) | part(c.y()) << 21 | part(c.z()) << 42;
  }

  double m_cell;
  std::vector<Posed> m_points;
  std::vector<Eigen::AlignedBox3f> m_boxes;
  Eigen::AlignedBox3f m_any;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> m_cells;
};

/// The 2nd and 98th percentiles of the valid points' z (a few stray points do not set the range).
std::pair<float, float> depthRange(const PointCloud& scan) {
  std::vector<float> z;
  const std::size_t stride = std::max<std::size_t>(1, scan.size() / 200000);
  for (std::size_t i = 0; i < scan.size(); i += stride)
    if (isValid(scan.points_mm[i]))
      z.push_back(scan.points_mm[i].z());
  if (z.empty())
    return {0.0f, 1.0f};
  const auto at = [&z](double q) {
    auto it = z.begin() + static_cast<std::ptrdiff_t>(q * double(z.size() - 1));
    std::nth_element(z.begin(), it, z.end());
    return *it;
  };
  const float lo = at(0.02), hi = at(0.98);
  return {lo, std::max(hi, lo + 1.0f)};
}

/// Throws Error for an unorganized scan, a tolerance that is not positive, detections without a
/// colour, or a detection naming a model that was not given.
void checkOverlayInputs(const PointCloud& scan, const std::vector<const PointCloud*>& models,
                        const std::vector<Detection>& detections, const std::vector<Rgb8>& colours,
                        double tolerance_mm) {
  if (!scan.isOrganized() || scan.size() != std::size_t(scan.width) * scan.height)
    throw Error("the depth image needs an organized scan (a sensor's grid of width x height); "
                "this one is a list of " +
                std::to_string(scan.size()) + " points");
  if (!(tolerance_mm > 0))
    throw Error("the depth image's tolerance must be positive");
  if (!detections.empty() && colours.empty())
    throw Error("the depth image needs a colour for the detections");
  for (const Detection& d : detections)
    if (d.model_index < 0 || std::size_t(d.model_index) >= models.size() ||
        !models[std::size_t(d.model_index)])
      throw Error("a detection names model " + std::to_string(d.model_index) +
                  ", which was not given for the depth image");
}

/// The valid model points of every detection at its pose, indexed in cells of `tolerance_mm`.
PosedModels poseModels(const std::vector<const PointCloud*>& models,
                       const std::vector<Detection>& detections, double tolerance_mm) {
  PosedModels posed(tolerance_mm);
  for (std::size_t k = 0; k < detections.size(); ++k) {
    const Detection& d = detections[k];
    const Eigen::Isometry3f T = d.T_scene_model.cast<float>();
    for (const Eigen::Vector3f& p : models[std::size_t(d.model_index)]->points_mm)
      if (isValid(p))
        posed.add(T * p, int(k));
  }
  posed.index();
  return posed;
}

/// Which detection tinted each cell (-1: none; empty without detections), and the sum of each
/// detection's tinted pixels (column, row).
struct Tinting {
  std::vector<std::int32_t> owner;
  std::vector<Eigen::Vector2d> pixel_sum;
};

/// Colours `out.rgb` (grey by depth between `near_z` and `far_z`, or the colour of the detection
/// whose posed model explains the point) and counts each detection's pixels in `out.marks`.
/// Reports progress from 0.2 to 0.9.
Tinting shadeAndTint(const PointCloud& scan, const PosedModels& posed, std::size_t detections,
                     const std::vector<Rgb8>& colours, float near_z, float far_z,
                     const ProgressFn& progress, DepthOverlay& out) {
  Tinting tinting;
  std::vector<Eigen::Vector2d>& tinted_sum = tinting.pixel_sum;
  std::vector<std::int32_t>& owner = tinting.owner;
  tinted_sum.assign(detections, Eigen::Vector2d::Zero());
  owner.assign(detections == 0 ? 0 : scan.size(), -1);
  for (std::uint32_t row = 0; row < scan.height; ++row) {
    if (row % 64 == 0)
      reportProgress(progress, 0.2 + 0.7 * double(row) / scan.height);
    for (std::uint32_t col = 0; col < scan.width; ++col) {
      const std::size_t i = std::size_t(row) * scan.width + col;
      const Eigen::Vector3f& p = scan.points_mm[i];
      if (!isValid(p))
        continue;
      // Near light, far dark; beyond the range clamped.
      const float shade = std::clamp((far_z - p.z()) / (far_z - near_z), 0.0f, 1.0f);
      const int k = detections == 0 ? -1 : posed.nearest(p);
      if (k < 0) {
        const auto grey = static_cast<std::uint8_t>(std::lround(45.0f + 195.0f * shade));
        out.rgb[i] = {grey, grey, grey};
        continue;
      }
      const Rgb8& c = colours[std::size_t(k) % colours.size()];
      // The colour stays recognisable; a little of the shade keeps the part's relief.
      const float keep = 0.75f + 0.25f * shade;
      out.rgb[i] = {static_cast<std::uint8_t>(std::lround(c[0] * keep)),
                    static_cast<std::uint8_t>(std::lround(c[1] * keep)),
                    static_cast<std::uint8_t>(std::lround(c[2] * keep))};
      out.marks[std::size_t(k)].pixels++;
      owner[i] = k;
      tinted_sum[std::size_t(k)] += Eigen::Vector2d(col, row);
    }
  }
  return tinting;
}

/// Each scan point's unit direction from the camera (the scan frame's origin); zero where none.
std::vector<Eigen::Vector3f> pixelDirections(const PointCloud& scan) {
  std::vector<Eigen::Vector3f> directions(scan.size(), Eigen::Vector3f::Zero());
  for (std::size_t i = 0; i < scan.size(); ++i)
    if (isValid(scan.points_mm[i]) && scan.points_mm[i].norm() > 0)
      directions[i] = scan.points_mm[i].normalized();
  return directions;
}

/// The pixel (column, row) of a scan `width` cells wide whose point's direction is nearest to
/// the direction towards `target` (scan frame, mm): where it appears. (-1, -1) when none lies
/// within 90° of it.
Eigen::Vector2d pixelTowards(const std::vector<Eigen::Vector3f>& directions, std::uint32_t width,
                             const Eigen::Vector3d& target) {
  Eigen::Vector2d best_px(-1, -1);
  if (!target.allFinite() || target.norm() <= 0)
    return best_px;
  const Eigen::Vector3f dir = target.normalized().cast<float>();
  float best = -2.0f;
  for (std::size_t i = 0; i < directions.size(); ++i) {
    const float c = directions[i].dot(dir);
    if (c > best) {
      best = c;
      best_px = Eigen::Vector2d(double(i % width), double(i / width));
    }
  }
  return best > 0 ? best_px : Eigen::Vector2d(-1, -1);
}

/// Puts each mark's label on its detection's tinted pixel nearest to the middle of them: the
/// middle itself may fall in a gap of the part (a frame, a bracket).
void placeLabels(const Tinting& tinting, std::uint32_t width,
                 std::vector<DepthOverlayMark>& marks) {
  std::vector<Eigen::Vector2d> middle(marks.size());
  std::vector<double> nearest_d2(marks.size(), std::numeric_limits<double>::max());
  for (std::size_t k = 0; k < marks.size(); ++k) {
    const std::size_t n = marks[k].pixels;
    middle[k] = n > 0 ? Eigen::Vector2d(tinting.pixel_sum[k] / double(n)) : Eigen::Vector2d(-1, -1);
  }
  for (std::size_t i = 0; i < tinting.owner.size(); ++i) {
    if (tinting.owner[i] < 0)
      continue;
    const auto k = std::size_t(tinting.owner[i]);
    const Eigen::Vector2d px(double(i % width), double(i / width));
    const double d2 = (px - middle[k]).squaredNorm();
    if (d2 < nearest_d2[k]) {
      nearest_d2[k] = d2;
      marks[k].label_px = px;
    }
  }
}

} // namespace

double depthOverlayTolerance_mm(const RecognitionParams& params) {
  return std::max({params.matching.verify_tolerance_mm, params.refine.inlier_distance_mm, 1.0});
}

DepthOverlay renderDepthOverlay(const PointCloud& scan,
                                const std::vector<const PointCloud*>& models,
                                const std::vector<Detection>& detections,
                                const std::vector<Rgb8>& colours, double tolerance_mm,
                                const ProgressFn& progress) {
  checkOverlayInputs(scan, models, detections, colours, tolerance_mm);
  DepthOverlay out;
  out.width = int(scan.width);
  out.height = int(scan.height);
  out.rgb.assign(scan.size(), kNoDepthColour);
  out.marks.resize(detections.size());

  const PosedModels posed = poseModels(models, detections, tolerance_mm);
  reportProgress(progress, 0.2);

  const auto [near_z, far_z] = depthRange(scan);
  const Tinting tinting =
      shadeAndTint(scan, posed, detections.size(), colours, near_z, far_z, progress, out);

  // Pixels towards a point: the camera is at the scan frame's origin, so the cell whose point's
  // direction is nearest to the point's direction is where it appears.
  const std::vector<Eigen::Vector3f> directions = pixelDirections(scan);
  placeLabels(tinting, scan.width, out.marks);
  for (std::size_t k = 0; k < detections.size(); ++k) {
    DepthOverlayMark& mark = out.marks[k];
    if (mark.pixels == 0)
      mark.label_px = pixelTowards(directions, scan.width, detections[k].centre_mm);
    for (const GripPoint& g : detections[k].grip_points_scene)
      mark.grips_px.push_back(pixelTowards(directions, scan.width, g.position_mm));
  }
  reportProgress(progress, 1.0);
  return out;
}

} // namespace scanpick::core
