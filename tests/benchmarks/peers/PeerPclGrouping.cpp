// PCL's correspondence grouping as a peer, as its tutorial (correspondence_grouping.cpp) builds
// it: uniform-sampling keypoints on model and scene, SHOT descriptors of the keypoints over the
// whole clouds, a kd-tree nearest neighbour in descriptor space (squared distance below 0.25) as a
// correspondence, pcl::GeometricConsistencyGrouping (threshold 5) for the instances, then
// pcl::IterativeClosestPoint from each instance's pose. The tutorial's radii are for one object
// in metres; here they scale with the part's diameter D and the voxel v (PeerSettings):
// model keypoints every max(0.025 D, v), scene keypoints every max(0.04 D, v), SHOT radius
// max(0.15 D, 8 v), consensus size max(0.04 D, 2 v). ICP: 20 iterations at correspondences up to
// 0.05 D, then 20 up to 2 v.
#include "PeerCommon.h"

#include <algorithm>
#include <chrono>
#include <pcl/correspondence.h>
#include <pcl/features/shot_omp.h>
#include <pcl/filters/uniform_sampling.h>
#include <pcl/recognition/cg/geometric_consistency.h>
#include <pcl/registration/icp.h>
#include <pcl/search/kdtree.h>

namespace scanpick::peers {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

using Cloud = pcl::PointCloud<pcl::PointXYZ>;
using Normals = pcl::PointCloud<pcl::Normal>;
using Descriptors = pcl::PointCloud<pcl::SHOT352>;

/// At most this many instances per view go to ICP, largest consensus first.
constexpr std::size_t kMaxInstances = 30;

struct Radii {
  double model_keypoints = 0, scene_keypoints = 0, descriptor = 0, consensus = 0;
  double icp_coarse = 0, icp_fine = 0;
};

Cloud::Ptr keypointsOf(const Cloud::Ptr& cloud, double radius) {
  Cloud::Ptr keypoints(new Cloud);
  pcl::UniformSampling<pcl::PointXYZ> sampling;
  sampling.setInputCloud(cloud);
  sampling.setRadiusSearch(radius);
  sampling.filter(*keypoints);
  return keypoints;
}

Descriptors::Ptr shotOf(const Cloud::Ptr& keypoints, const Cloud::Ptr& surface,
                        const Normals::Ptr& normals, double radius) {
  Descriptors::Ptr descriptors(new Descriptors);
  pcl::SHOTEstimationOMP<pcl::PointXYZ, pcl::Normal, pcl::SHOT352> shot(2);
  shot.setRadiusSearch(radius);
  shot.setInputCloud(keypoints);
  shot.setInputNormals(normals);
  shot.setSearchSurface(surface);
  shot.compute(*descriptors);
  return descriptors;
}

class PclGrouping final : public PeerMethod {
public:
  void train(const std::vector<PeerModel>& models, const PeerSettings& settings) override {
    const double D = settings.diameter_mm, v = settings.voxel_mm;
    m_radii.model_keypoints = std::max(0.025 * D, v);
    m_radii.scene_keypoints = std::max(0.04 * D, v);
    m_radii.descriptor = std::max(0.15 * D, 8 * v);
    m_radii.consensus = std::max(0.04 * D, 2 * v);
    m_radii.icp_coarse = 0.05 * D;
    m_radii.icp_fine = 2 * v;
    m_views.clear();
    for (const auto& m : models) {
      View view;
      view.cloud.reset(new Cloud);
      Normals::Ptr normals(new Normals);
      for (std::size_t i = 0; i < m.sampled_mm.size(); ++i) {
        const auto& p = m.sampled_mm.points_mm[i];
        const auto& n = m.sampled_mm.normals[i];
        view.cloud->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
        normals->push_back(pcl::Normal(n.x(), n.y(), n.z()));
      }
      view.keypoints = keypointsOf(view.cloud, m_radii.model_keypoints);
      view.descriptors = shotOf(view.keypoints, view.cloud, normals, m_radii.descriptor);
      view.tree.setInputCloud(view.descriptors);
      m_views.push_back(std::move(view));
    }
  }

  MethodOutput detect(const PeerScene& scene) override {
    MethodOutput out;
    if (scene.points->size() < 10)
      return out;
    const auto start = Clock::now();
    const Cloud::Ptr keypoints = keypointsOf(scene.points, m_radii.scene_keypoints);
    const Descriptors::Ptr descriptors =
        shotOf(keypoints, scene.points, scene.normals, m_radii.descriptor);
    std::vector<std::pair<std::size_t, Eigen::Matrix4f>> instances;
    for (std::size_t v = 0; v < m_views.size(); ++v) {
      const View& view = m_views[v];
      pcl::CorrespondencesPtr correspondences(new pcl::Correspondences);
      std::vector<int> index(1);
      std::vector<float> sq(1);
      for (std::size_t i = 0; i < descriptors->size(); ++i) {
        if (!std::isfinite((*descriptors)[i].descriptor[0]))
          continue;
        if (view.tree.nearestKSearch((*descriptors)[i], 1, index, sq) == 1 && sq[0] < 0.25f)
          correspondences->emplace_back(index[0], int(i), sq[0]);
      }
      std::vector<Eigen::Matrix4f, Eigen::aligned_allocator<Eigen::Matrix4f>> poses;
      std::vector<pcl::Correspondences> clustered;
      pcl::GeometricConsistencyGrouping<pcl::PointXYZ, pcl::PointXYZ> grouping;
      grouping.setGCSize(m_radii.consensus);
      grouping.setGCThreshold(5);
      grouping.setInputCloud(view.keypoints);
      grouping.setSceneCloud(keypoints);
      grouping.setModelSceneCorrespondences(correspondences);
      grouping.recognize(poses, clustered);
      std::vector<std::size_t> order(poses.size());
      for (std::size_t k = 0; k < order.size(); ++k)
        order[k] = k;
      std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return clustered[a].size() > clustered[b].size();
      });
      if (order.size() > kMaxInstances)
        order.resize(kMaxInstances);
      for (const std::size_t k : order)
        instances.emplace_back(v, poses[k]);
    }
    out.matching_ms = msSince(start);

    const auto refine_start = Clock::now();
    pcl::IterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ> icp;
    icp.setInputTarget(scene.points);
    // One kd-tree of the scene for every hypothesis: ICP would otherwise rebuild it per call.
    pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
    tree->setInputCloud(scene.points);
    icp.setSearchMethodTarget(tree, true);
    icp.setMaximumIterations(20);
    icp.setTransformationEpsilon(1e-10);
    Cloud aligned;
    for (const auto& [v, pose] : instances) {
      icp.setInputSource(m_views[v].cloud);
      Eigen::Matrix4f T = pose;
      for (const double distance : {m_radii.icp_coarse, m_radii.icp_fine}) {
        icp.setMaxCorrespondenceDistance(distance);
        icp.align(aligned, T);
        if (icp.hasConverged())
          T = icp.getFinalTransformation();
      }
      Hypothesis h;
      h.view = v;
      h.T_scene_model.matrix() = T.cast<double>();
      const Eigen::Quaterniond q(h.T_scene_model.linear());
      h.T_scene_model.linear() = q.normalized().toRotationMatrix();
      if (h.T_scene_model.matrix().allFinite())
        out.hypotheses.push_back(h);
    }
    out.refine_ms = msSince(refine_start);
    return out;
  }

  std::string describe() const override {
    return "PCL uniform keypoints " + std::to_string(m_radii.model_keypoints) + " / " +
           std::to_string(m_radii.scene_keypoints) + " mm, SHOT radius " +
           std::to_string(m_radii.descriptor) + " mm, geometric consistency " +
           std::to_string(m_radii.consensus) + " mm x 5, ICP " +
           std::to_string(m_radii.icp_coarse) + " then " + std::to_string(m_radii.icp_fine) + " mm";
  }

private:
  struct View {
    Cloud::Ptr cloud, keypoints;
    Descriptors::Ptr descriptors;
    pcl::KdTreeFLANN<pcl::SHOT352> tree;
  };
  Radii m_radii;
  std::vector<View> m_views;
};

} // namespace

std::unique_ptr<PeerMethod> makePclGrouping() {
  return std::make_unique<PclGrouping>();
}

} // namespace scanpick::peers
