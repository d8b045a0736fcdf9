#include "core/grasp/GraspPoint.h"

#include "core/common/Error.h"

#include <Eigen/Eigenvalues>
#include <algorithm>

namespace scanpick::core::grasp {

std::vector<GraspPoint> graspPoints(const std::vector<GripPoint>& grips_model,
                                    const std::vector<GraspSpec>& specs) {
  std::vector<GraspPoint> out;
  if (specs.empty()) {
    for (const auto& taught : grips_model) {
      const GripPoint g = checkedGrip(taught);
      out.push_back(
          {g.name, g.position_mm, g.approach.value_or(Eigen::Vector3d::UnitZ()), g.closing_axis});
    }
    return out;
  }
  for (const auto& spec : specs) {
    const GripPoint* grip = nullptr;
    for (const auto& g : grips_model)
      if (g.name == spec.grip)
        grip = &g;
    if (grip == nullptr) {
      std::string names;
      for (const auto& g : grips_model)
        names += (names.empty() ? "" : ", ") + g.name;
      throw Error("grip '" + spec.grip + "' is not a grip point of the model: use one of [" +
                  names + "] or teach it with --grip");
    }
    GraspPoint p{grip->name, grip->position_mm,
                 unitDirection(spec.approach, "the approach of grip '" + spec.grip + "'"),
                 std::nullopt};
    if (spec.closing_axis)
      p.closing_axis = closingAcross(*spec.closing_axis, p.approach, spec.grip);
    out.push_back(std::move(p));
  }
  return out;
}

Eigen::Vector3d surfaceApproach(const PointCloud& scan_mm, const Eigen::Vector3d& point_mm) {
  std::vector<std::pair<double, Eigen::Vector3d>> near;
  for (const auto& p : scan_mm.points_mm)
    if (isValid(p))
      near.emplace_back((p.cast<double>() - point_mm).squaredNorm(), p.cast<double>());
  if (near.size() < kSurfaceNeighbours)
    throw Error("too few scan points around the grip point to find the surface's normal");
  std::partial_sort(near.begin(), near.begin() + std::ptrdiff_t(kSurfaceNeighbours), near.end(),
                    [](const auto& a, const auto& b) { return a.first < b.first; });
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < kSurfaceNeighbours; ++i)
    mean += near[i].second;
  mean /= double(kSurfaceNeighbours);
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < kSurfaceNeighbours; ++i)
    covariance += (near[i].second - mean) * (near[i].second - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  // Eigenvalues ascending: a plane has one small and two large ones; a line two small ones.
  if (solver.eigenvalues()(1) <= 1e-9 * solver.eigenvalues()(2))
    throw Error("the scan points around the grip point lie on a line: no surface normal there");
  Eigen::Vector3d normal = solver.eigenvectors().col(0);
  // Away from the camera at the origin: the tool comes from the camera's side into the part.
  if (normal.dot(mean) < 0)
    normal = -normal;
  return normal.normalized();
}

} // namespace scanpick::core::grasp
