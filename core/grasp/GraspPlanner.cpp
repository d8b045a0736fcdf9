#include "core/grasp/GraspPlanner.h"

#include "core/common/Error.h"
#include "core/grasp/PointGrid.h"
#include "core/grasp/ToolVolume.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <tuple>

namespace scanpick::core::grasp {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
/// Largest turn (degrees) of the approach between poses the scan cannot tell apart that still
/// counts as the same grasp.
constexpr double kMaxAmbiguousTurnDeg = 10.0;

std::string format(const char* fmt, double a, double b = 0.0) {
  char buf[128];
  std::snprintf(buf, sizeof buf, fmt, a, b);
  return buf;
}

/// Points of the scene that belong to detected parts: (point index, detection), sorted.
using Owned = std::vector<std::pair<std::uint32_t, std::int32_t>>;

Owned partPoints(const PointGrid& grid, const std::vector<Detection>& detections,
                 const std::vector<GraspModel>& models, double tolerance) {
  Owned owned;
  const double tol_sq = tolerance * tolerance;
  for (std::size_t d = 0; d < detections.size(); ++d) {
    const Eigen::Isometry3d& T = detections[d].T_scene_model;
    for (const auto& m : models[std::size_t(detections[d].model_index)].cloud_mm.points_mm) {
      if (!isValid(m))
        continue;
      const Eigen::Vector3d p = T * m.cast<double>();
      const Eigen::Vector3d r = Eigen::Vector3d::Constant(tolerance);
      grid.forEachNear(Eigen::AlignedBox3d(p - r, p + r), [&](std::uint32_t i) {
        if ((grid.points()[i].cast<double>() - p).squaredNorm() <= tol_sq)
          owned.emplace_back(i, std::int32_t(d));
        return true;
      });
    }
  }
  std::sort(owned.begin(), owned.end());
  owned.erase(std::unique(owned.begin(), owned.end()), owned.end());
  return owned;
}

/// The detection a point belongs to: `picked` when it is one of its points, else the lowest
/// other, else -1.
int ownerOf(const Owned& owned, std::uint32_t i, int picked) {
  auto it = std::lower_bound(owned.begin(), owned.end(), std::make_pair(i, std::int32_t(-1)));
  int other = -1;
  for (; it != owned.end() && it->first == i; ++it) {
    if (it->second == picked)
      return picked;
    if (other < 0)
      other = it->second;
  }
  return other;
}

double occlusion(const PointGrid& grid, const Owned& owned, const Detection& det, int index,
                 const PointCloud& model_cloud, const GraspPlanParams& p) {
  std::vector<Eigen::Vector3d> samples;
  const std::size_t valid = model_cloud.validCount();
  if (valid == 0)
    return 0.0;
  const std::size_t stride =
      std::max<std::size_t>(1, valid / std::size_t(std::max(1, p.max_occlusion_samples)));
  std::size_t seen = 0;
  for (const auto& m : model_cloud.points_mm)
    if (isValid(m) && seen++ % stride == 0)
      samples.push_back(det.T_scene_model * m.cast<double>());
  const double r = p.occlusion_radius_mm;
  std::size_t covered = 0;
  for (const auto& m : samples) {
    Eigen::AlignedBox3d box(m);
    box.extend(m + p.approach_length_mm * p.up);
    box.min().array() -= r;
    box.max().array() += r;
    bool hit = false;
    grid.forEachNear(box, [&](std::uint32_t i) {
      const Eigen::Vector3d v = grid.points()[i].cast<double>() - m;
      const double h = v.dot(p.up);
      if (h > p.part_tolerance_mm && (v - h * p.up).squaredNorm() <= r * r &&
          ownerOf(owned, i, index) != index)
        hit = true;
      return !hit;
    });
    covered += hit ? 1 : 0;
  }
  return double(covered) / double(samples.size());
}

void checkParams(const GraspPlanParams& p) {
  const auto bad = [](double v, double lo) { return !std::isfinite(v) || v < lo; };
  if (bad(p.approach_length_mm, 0.0) || bad(p.part_tolerance_mm, 0.0) || bad(p.clearance_mm, 0.0) ||
      bad(p.max_tilt_deg, 0.0) || p.max_tilt_deg > 180.0 || !(p.grid_cell_mm > 0.0) ||
      !(p.bin_sample_mm > 0.0) || bad(p.occlusion_radius_mm, 0.0) || p.max_collision_points < 0 ||
      !std::isfinite(p.grid_cell_mm) || !std::isfinite(p.bin_sample_mm))
    throw Error("grasp planning: a parameter is out of range (lengths >= 0, cell and sample "
                "sizes > 0, max_tilt_deg in [0, 180], max_collision_points >= 0)");
  if (!p.up.allFinite() || std::abs(p.up.norm() - 1.0) > 1e-3)
    throw Error("grasp planning: up must be a unit vector");
}

/// The solid's point collisions: appends a rejection per kind of thing hit.
void checkPoints(const PointGrid& grid, const Owned& owned, int picked, const ToolSolid& solid,
                 const Eigen::Isometry3d& T_scene_tool, const GraspPlanParams& p,
                 std::vector<Rejection>& out) {
  const Eigen::Isometry3d T_tool_scene = T_scene_tool.inverse();
  std::map<int, int> hits; // owner (-1: nothing detected) → points
  grid.forEachNear(solidBounds(solid, T_scene_tool), [&](std::uint32_t i) {
    if (insideSolid(solid, T_tool_scene * grid.points()[i].cast<double>()))
      ++hits[ownerOf(owned, i, picked)];
    return true;
  });
  for (const auto& [owner, count] : hits) {
    if (count <= p.max_collision_points)
      continue;
    const std::string n = std::to_string(count);
    if (owner == picked) {
      if (solid.checks_part)
        out.push_back(
            {RejectKind::PickedPart, solid.name + " hits the picked part itself (" + n +
                                         " points): opening too small, or the grip is too deep"});
    } else if (owner >= 0) {
      out.push_back({RejectKind::PartCollision,
                     solid.name + " hits part #" + std::to_string(owner) + " (" + n + " points)"});
    } else {
      out.push_back({RejectKind::SceneCollision, solid.name + " hits " + n + " scan points"});
    }
  }
}

} // namespace

const char* toString(PickOrder order) {
  switch (order) {
  case PickOrder::HighestFirst:
    return "highest-first";
  case PickOrder::LeastOccluded:
    return "least-occluded";
  case PickOrder::BestScore:
    return "best-score";
  }
  return "?";
}

PickOrder parsePickOrder(const std::string& name) {
  for (PickOrder o : {PickOrder::HighestFirst, PickOrder::LeastOccluded, PickOrder::BestScore})
    if (name == toString(o))
      return o;
  throw Error("unknown pick order '" + name +
              "': use \"highest-first\", \"least-occluded\" or \"best-score\"");
}

const char* toString(RejectKind kind) {
  switch (kind) {
  case RejectKind::LowScore:
    return "low-score";
  case RejectKind::Ambiguous:
    return "ambiguous";
  case RejectKind::TiltTooLarge:
    return "tilt";
  case RejectKind::SceneCollision:
    return "scene-collision";
  case RejectKind::PartCollision:
    return "part-collision";
  case RejectKind::PickedPart:
    return "picked-part";
  case RejectKind::BinCollision:
    return "bin-collision";
  }
  return "?";
}

Eigen::Isometry3d toolPose(const Eigen::Isometry3d& T_scene_model, const GraspPoint& grasp) {
  const Eigen::Matrix3d R = T_scene_model.linear();
  const Eigen::Vector3d z = (R * grasp.approach).normalized();
  Eigen::Vector3d x_hint =
      grasp.closing_axis ? Eigen::Vector3d(R * *grasp.closing_axis) : Eigen::Vector3d::UnitX();
  if (!grasp.closing_axis && std::abs(z.x()) > 0.9)
    x_hint = Eigen::Vector3d::UnitY();
  const Eigen::Vector3d x = (x_hint - x_hint.dot(z) * z).normalized();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear().col(0) = x;
  T.linear().col(1) = z.cross(x);
  T.linear().col(2) = z;
  T.translation() = T_scene_model * grasp.position_mm;
  return T;
}

namespace {

/// Rejects the candidate as Ambiguous when its grasp moves or turns more than tolerated between
/// the detection's pose and the poses the scan cannot tell from it (alternatives, free turns).
/// At an alternative pose the grasp nearest the candidate's tool pose among the model's `grasps`
/// counts: a symmetric part's alternative puts another grasp where this one was, and the tool
/// grips the part there whichever pose is right.
void checkAmbiguous(const Detection& det, const std::vector<GraspPoint>& grasps,
                    const GraspPlanParams& p, GraspCandidate& c) {
  const Eigen::Vector3d approach = c.T_scene_tool.linear().col(2);
  double moved = 0.0, turned = 0.0;
  const auto offset = [&](const Eigen::Isometry3d& T_alt, const GraspPoint& grasp) {
    const Eigen::Isometry3d T_tool = toolPose(T_alt, grasp);
    return std::make_pair((T_tool.translation() - c.T_scene_tool.translation()).norm(),
                          std::acos(std::clamp(T_tool.linear().col(2).dot(approach), -1.0, 1.0)) /
                              kDeg);
  };
  for (const auto& alt : det.alternative_poses) {
    auto [alt_moved, alt_turned] = offset(alt, grasps[std::size_t(c.grasp)]);
    for (const GraspPoint& other : grasps) {
      const auto [distance, angle] = offset(alt, other);
      if (angle <= kMaxAmbiguousTurnDeg &&
          (distance < alt_moved || alt_turned > kMaxAmbiguousTurnDeg)) {
        alt_moved = distance;
        alt_turned = angle;
      }
    }
    moved = std::max(moved, alt_moved);
    turned = std::max(turned, alt_turned);
  }
  if (det.free_turn_axis) {
    const Eigen::Vector3d a = det.free_turn_axis->direction.normalized();
    const Eigen::Vector3d v = c.T_scene_tool.translation() - det.free_turn_axis->point_mm;
    // A turn about the axis moves the grip by up to twice its distance from the axis.
    moved = std::max(moved, 2.0 * (v - v.dot(a) * a).norm());
    turned =
        std::max(turned, 2.0 * std::asin(std::clamp(approach.cross(a).norm(), 0.0, 1.0)) / kDeg);
  }
  if (moved > p.part_tolerance_mm || turned > kMaxAmbiguousTurnDeg)
    c.rejections.push_back(
        {RejectKind::Ambiguous,
         format("the grasp moves up to %.1f mm (turns %.0f deg) between poses the scan "
                "cannot tell apart",
                moved, turned)});
}

/// Grasp `g` of detection `d` with the tool pose and pregrasp in the scene, its tilt, height and
/// occlusion `occ`, rejected for a low score, ambiguity or tilt (collisions are checked apart).
GraspCandidate candidateFor(const Detection& det, std::size_t d, std::size_t g,
                            const std::vector<GraspPoint>& grasps, double occ,
                            const GraspPlanParams& p) {
  const GraspPoint& grasp = grasps[g];
  GraspCandidate c;
  c.detection = int(d);
  c.grasp = int(g);
  c.grip = grasp.name;
  c.T_scene_tool = toolPose(det.T_scene_model, grasp);
  c.T_scene_pregrasp = c.T_scene_tool * Eigen::Translation3d(0.0, 0.0, -p.approach_length_mm);
  const Eigen::Vector3d approach = c.T_scene_tool.linear().col(2);
  c.tilt_deg = std::acos(std::clamp(approach.dot(-p.up), -1.0, 1.0)) / kDeg;
  c.height_mm = c.T_scene_tool.translation().dot(p.up);
  c.occlusion = occ;
  c.score = det.score;
  if (det.score < p.min_score)
    c.rejections.push_back(
        {RejectKind::LowScore, format("score %.3f < minimum %.3f", det.score, p.min_score)});
  if (p.reject_ambiguous)
    checkAmbiguous(det, grasps, p, c);
  if (c.tilt_deg > p.max_tilt_deg)
    c.rejections.push_back(
        {RejectKind::TiltTooLarge, format("approach tilted %.1f deg from straight down (max %.1f)",
                                          c.tilt_deg, p.max_tilt_deg)});
  return c;
}

/// Appends each tool solid's collisions with the scan's points and, when there is one, the bin.
void checkCollisions(const PointGrid& grid, const Owned& owned, int picked,
                     const std::vector<ToolSolid>& solids, const std::optional<BinBox>& bin,
                     const GraspPlanParams& p, GraspCandidate& c) {
  for (const auto& solid : solids) {
    checkPoints(grid, owned, picked, solid, c.T_scene_tool, p, c.rejections);
    if (!bin)
      continue;
    for (const auto& q : solidSurfaceSamples(solid, p.bin_sample_mm)) {
      const std::string hit = binCollision(*bin, c.T_scene_tool * q);
      if (!hit.empty()) {
        c.rejections.push_back({RejectKind::BinCollision, solid.name + " hits the " + hit});
        break;
      }
    }
  }
}

/// Sorts the picks by the pick order (ties by detection, then grasp) and, with one_per_part,
/// keeps each detection's first.
void orderPicks(std::vector<GraspCandidate>& picks, const GraspPlanParams& p) {
  const auto key = [&p](const GraspCandidate& c) {
    switch (p.order) {
    case PickOrder::LeastOccluded:
      return std::make_tuple(c.occlusion, -c.height_mm);
    case PickOrder::BestScore:
      return std::make_tuple(-c.score, -c.height_mm);
    default:
      return std::make_tuple(-c.height_mm, 0.0);
    }
  };
  std::stable_sort(picks.begin(), picks.end(),
                   [&](const GraspCandidate& a, const GraspCandidate& b) {
                     return std::make_tuple(key(a), a.detection, a.grasp) <
                            std::make_tuple(key(b), b.detection, b.grasp);
                   });
  if (p.one_per_part) {
    std::vector<GraspCandidate> kept;
    std::vector<int> taken;
    for (auto& c : picks)
      if (std::find(taken.begin(), taken.end(), c.detection) == taken.end()) {
        taken.push_back(c.detection);
        kept.push_back(std::move(c));
      }
    picks = std::move(kept);
  }
}

} // namespace

PickList planGrasps(const PointCloud& scene_mm, const std::vector<Detection>& detections,
                    const std::vector<GraspModel>& models, const Gripper& gripper,
                    const std::optional<BinBox>& bin, const GraspPlanParams& p) {
  checkParams(p);
  for (const auto& d : detections)
    if (d.model_index < 0 || std::size_t(d.model_index) >= models.size())
      throw Error("grasp planning: a detection names model " + std::to_string(d.model_index) +
                  ", but " + std::to_string(models.size()) + " model(s) were given");
  std::vector<ToolSolid> solids;
  for (const auto& s : toolSolids(gripper))
    solids.push_back(sweptSolid(s, p.approach_length_mm, p.clearance_mm));
  const PointGrid grid(scene_mm.points_mm, p.grid_cell_mm);
  const Owned owned = partPoints(grid, detections, models, p.part_tolerance_mm);

  std::vector<GraspCandidate> all;
  for (std::size_t d = 0; d < detections.size(); ++d) {
    const Detection& det = detections[d];
    const GraspModel& model = models[std::size_t(det.model_index)];
    const double occ =
        model.grasps.empty() ? 0.0 : occlusion(grid, owned, det, int(d), model.cloud_mm, p);
    for (std::size_t g = 0; g < model.grasps.size(); ++g) {
      GraspCandidate c = candidateFor(det, d, g, model.grasps, occ, p);
      checkCollisions(grid, owned, int(d), solids, bin, p, c);
      all.push_back(std::move(c));
    }
  }

  PickList out;
  for (auto& c : all)
    (c.feasible() ? out.picks : out.rejected).push_back(std::move(c));
  orderPicks(out.picks, p);
  return out;
}

} // namespace scanpick::core::grasp
