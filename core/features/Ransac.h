#pragma once
/// @file Ransac.h
/// Plain RANSAC over a PCL sample consensus model, for feature extraction.

#include <Eigen/Core>
#include <pcl/point_types.h>
#include <pcl/sample_consensus/sac_model.h>

namespace scanpick::core {

/// RANSAC's trials as pcl::RandomSampleConsensus::computeModel runs them on one thread (PCL 1.13,
/// probability 0.99): the same samples, the same stopping rule, so the same model, without two
/// costs of PCL's loop. Its OpenMP critical section around every sample draw is named, so one
/// lock for the whole process: the line and circle searches, which run side by side, waited on
/// each other at every trial (libgomp's spin lock took 3 % of a PhoXi scene's CPU time). And its
/// final selection of the winner's inliers, which extractFeatures does anew over all remaining
/// keypoints, is left out.
///
/// Scores each sample's model by `model.countWithinDistance(c, threshold_mm)` and stops when 0.99
/// of the samples drawn would have held only inliers at the best ratio so far, or after
/// `max_iterations` (>= 1) + 1 trials, as PCL does; `best` gets the coefficients with the most
/// inliers. False when no sample made a model with an inlier.
bool ransacModel(pcl::SampleConsensusModel<pcl::PointXYZ>& model, double threshold_mm,
                 int max_iterations, Eigen::VectorXf& best);

} // namespace scanpick::core
