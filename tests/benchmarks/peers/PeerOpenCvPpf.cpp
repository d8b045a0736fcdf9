// OpenCV's surface matching (opencv_contrib surface_matching, Drost et al. 2010) as a peer.
//
// Parameters are those of OpenCV's sample ppf_load_match.cpp: PPF3DDetector(0.025, 0.05) (model
// sampled at 0.025 x its diameter, pair distances quantized at 0.05 x), match(scene, 1/40, 0.05)
// (every 40th sampled scene point is a reference; the scene sampled at 0.05 x the model's
// diameter) and ICP(100, 0.005, 2.5, 8) on the best poses. Two departures, both needed on a bin:
// - OpenCV quantizes a cloud on a (1/step)^3 grid over the cloud's own box, each axis divided
//   alike: a flat part's thin axis gets cells far finer than its diameter says (and a model of
//   tens of thousands of points, whose training takes many minutes), and a scene's cells scale
//   with the bin, not with the model's diameter its documentation names. So model and scene are
//   first voxel-sampled here at those steps times the model's diameter (core voxelDownsample,
//   normals averaged) and handed over with steps that keep OpenCV's grid from merging them
//   further.
// - The sample keeps the best 2 poses of one object; a bin holds many, so the best kMaxPoses go to
//   ICP and the shared scoring (PeerCommon.h) keeps the confirmed ones.
#include "PeerCommon.h"
#include "core/preprocess/Downsample.h"

#include <algorithm>
#include <chrono>
#include <opencv2/core.hpp>
#include <opencv2/surface_matching.hpp>

namespace scanpick::peers {
namespace {

constexpr double kRelativeSamplingStep = 0.025;
constexpr double kRelativeDistanceStep = 0.05;
/// The finest grid OpenCV's scene quantization is asked for: it allocates (1/step)^3 cells.
constexpr double kFinestSceneGrid = 1.0 / 150.0;
constexpr std::size_t kMaxPoses = 20;

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

/// An N x 6 CV_32F matrix (x, y, z, nx, ny, nz) of the valid points with finite normals.
cv::Mat toMat(const std::vector<Eigen::Vector3f>& points,
              const std::vector<Eigen::Vector3f>& normals) {
  cv::Mat m(0, 6, CV_32F);
  m.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite() || !normals[i].allFinite() || normals[i].squaredNorm() < 0.5f)
      continue;
    const float row[6] = {points[i].x(),  points[i].y(),  points[i].z(),
                          normals[i].x(), normals[i].y(), normals[i].z()};
    m.push_back(cv::Mat(1, 6, CV_32F, const_cast<float*>(row)));
  }
  return m;
}

class OpenCvPpf final : public PeerMethod {
public:
  explicit OpenCvPpf(const OpenCvPpfOptions& options) : m_options(options) {}

  void train(const std::vector<PeerModel>& models, const PeerSettings& settings) override {
    m_settings = settings;
    m_views.clear();
    for (std::size_t v = 0; v < models.size(); ++v) {
      View view;
      view.detector = std::make_unique<cv::ppf_match_3d::PPF3DDetector>(kRelativeSamplingStep,
                                                                        kRelativeDistanceStep);
      const core::PointCloud sampled =
          core::voxelDownsample(models[v].cloud_mm, kRelativeSamplingStep * models[v].diameter_mm);
      view.detector->trainModel(toMat(sampled.points_mm, sampled.normals));
      view.icp_model = toMat(models[v].sampled_mm.points_mm, models[v].sampled_mm.normals);
      view.diameter_mm = models[v].diameter_mm;
      m_views.push_back(std::move(view));
    }
  }

  MethodOutput detect(const PeerScene& scene) override {
    MethodOutput out;
    if (scene.points->empty())
      return out;
    core::PointCloud prepared;
    prepared.width = std::uint32_t(scene.points->size());
    for (std::size_t i = 0; i < scene.points->size(); ++i) {
      const auto& p = (*scene.points)[i];
      const auto& n = (*scene.normals)[i];
      prepared.points_mm.emplace_back(p.x, p.y, p.z);
      prepared.normals.emplace_back(n.normal_x, n.normal_y, n.normal_z);
    }
    const cv::Mat icp_scene = toMat(prepared.points_mm, prepared.normals);
    for (std::size_t v = 0; v < m_views.size(); ++v) {
      const auto start = Clock::now();
      const core::PointCloud sampled =
          core::voxelDownsample(prepared, m_options.scene_distance * m_views[v].diameter_mm);
      const cv::Mat match_scene = toMat(sampled.points_mm, sampled.normals);
      if (match_scene.rows < 3)
        continue;
      const Eigen::AlignedBox3f box = core::boundingBox(sampled);
      const double extent = double(box.sizes().maxCoeff());
      const double relative = std::clamp(m_options.scene_distance * m_views[v].diameter_mm /
                                             std::max(extent, 1e-6) * 0.5,
                                         kFinestSceneGrid, 1.0);
      std::vector<cv::ppf_match_3d::Pose3DPtr> poses;
      m_views[v].detector->match(match_scene, poses, m_options.scene_sample_step, relative);
      out.matching_ms += msSince(start);

      const auto refine_start = Clock::now();
      if (poses.size() > kMaxPoses)
        poses.resize(kMaxPoses);
      if (!poses.empty() && icp_scene.rows >= 3) {
        cv::ppf_match_3d::ICP icp(100, 0.005f, 2.5f, 8);
        icp.registerModelToScene(m_views[v].icp_model, icp_scene, poses);
      }
      for (const auto& pose : poses) {
        Hypothesis h;
        h.view = v;
        Eigen::Matrix4d T;
        for (int r = 0; r < 4; ++r)
          for (int c = 0; c < 4; ++c)
            T(r, c) = pose->pose(r, c);
        h.T_scene_model.matrix() = T;
        // OpenCV composes poses in double; an orthonormal rotation is restored for the results.
        const Eigen::Quaterniond q(h.T_scene_model.linear());
        h.T_scene_model.linear() = q.normalized().toRotationMatrix();
        if (h.T_scene_model.matrix().allFinite())
          out.hypotheses.push_back(h);
      }
      out.refine_ms += msSince(refine_start);
    }
    return out;
  }

  std::string describe() const override {
    return "OpenCV PPF3DDetector(0.025, 0.05), match(" +
           std::to_string(m_options.scene_sample_step) + ", scene sampled at " +
           std::to_string(m_options.scene_distance) + " x diameter), best " +
           std::to_string(kMaxPoses) + " poses, ICP(100, 0.005, 2.5, 8)";
  }

private:
  struct View {
    std::unique_ptr<cv::ppf_match_3d::PPF3DDetector> detector;
    cv::Mat icp_model;
    double diameter_mm = 0.0;
  };
  OpenCvPpfOptions m_options;
  PeerSettings m_settings;
  std::vector<View> m_views;
};

} // namespace

std::unique_ptr<PeerMethod> makeOpenCvPpf(const OpenCvPpfOptions& options) {
  return std::make_unique<OpenCvPpf>(options);
}

} // namespace scanpick::peers
