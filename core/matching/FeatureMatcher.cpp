#include "core/matching/FeatureMatcher.h"

#include "core/common/Error.h"
#include "core/common/ParallelProgress.h"
#include "core/matching/FeatureIndex.h"
#include "core/matching/RigidFit.h"

#include <algorithm>
#include <atomic>
#include <climits>
#include <cmath>
#include <map>
#include <tbb/parallel_for.h>

namespace scanpick::core {
namespace {

using Vec3 = Eigen::Vector3d;

double sizeTolerance(const MatchingParams& p, FeatureType type) {
  return type == FeatureType::Line ? p.length_tolerance_mm : p.radius_tolerance_mm;
}

bool descriptorsAgree(const Feature& a, const Feature& b, const MatchingParams& p) {
  return a.type == b.type &&
         std::abs(static_cast<double>(a.size_mm) - b.size_mm) <= sizeTolerance(p, a.type);
}

bool isAvailable(const std::vector<char>& mask, int i) {
  return mask.empty() || mask[static_cast<std::size_t>(i)] != 0;
}

/// Everything the search reads, computed once per call and shared read-only by the tasks.
struct Prepared {
  const FeatureList& model;
  const FeatureList& scene;
  const MatchingParams& params;
  const std::vector<char>& available;
  FeatureIndex index;
  std::vector<Vec3> mc, md, sc, sd; // centres and unit axes in double precision
  /// For each scene feature j: all scene features sorted by distance from j (distance, index).
  /// A toroid around T1 lies in the shell | |T2 − T1| − |M2 − M1| | ≤ Δp, found by binary search.
  std::vector<std::vector<std::pair<double, int>>> shells;
  /// Pooled search: features a pose must confirm to be kept (the score threshold, at least 2).
  int min_pool_count = 2;

  Prepared(const FeatureList& m, const FeatureList& s, const MatchingParams& p,
           const std::vector<char>& avail, bool with_shells)
      : model(m), scene(s), params(p), available(avail), index(s),
        min_pool_count(
            std::max(2, static_cast<int>(std::ceil(p.score_threshold * double(m.size()) - 1e-9)))) {
    for (const auto& f : m) {
      mc.push_back(f.centre_mm.cast<double>());
      md.push_back(f.direction.cast<double>().normalized());
    }
    for (const auto& f : s) {
      sc.push_back(f.centre_mm.cast<double>());
      sd.push_back(f.direction.cast<double>().normalized());
    }
    if (!with_shells)
      return;
    shells.resize(s.size());
    tbb::parallel_for(std::size_t{0}, s.size(), [&](std::size_t j) {
      auto& shell = shells[j];
      shell.reserve(s.size());
      for (std::size_t t = 0; t < s.size(); ++t)
        shell.emplace_back((sc[t] - sc[j]).norm(), static_cast<int>(t));
      std::sort(shell.begin(), shell.end());
    });
  }
};

/// Scores T; gives up (returns count -1) as soon as `min_count` can no longer be reached.
MatchCandidate scoreWithBound(const Prepared& prep, const Eigen::Isometry3d& T, int min_count,
                              int* count_out) {
  const auto& p = prep.params;
  const auto n_model = static_cast<int>(prep.model.size());
  MatchCandidate out;
  out.T_scene_model = T;
  std::vector<char> used(prep.scene.size(), 0);
  int count = 0;
  double residual = 0.0;
  for (int m = 0; m < n_model; ++m) {
    if (count + (n_model - m) < min_count) {
      *count_out = -1;
      return out;
    }
    const Feature& mf = prep.model[static_cast<std::size_t>(m)];
    const Vec3 pos = T * prep.mc[static_cast<std::size_t>(m)];
    const Vec3 dir = T.linear() * prep.md[static_cast<std::size_t>(m)];
    int best = -1;
    double best_dist = 0.0;
    for (int s :
         prep.index.within(pos.cast<float>(), static_cast<float>(p.position_tolerance_mm))) {
      if (used[static_cast<std::size_t>(s)] || !isAvailable(prep.available, s) ||
          !descriptorsAgree(mf, prep.scene[static_cast<std::size_t>(s)], p))
        continue;
      if (axisAngle(dir, prep.sd[static_cast<std::size_t>(s)]) > p.orientation_tolerance_rad)
        continue;
      const double d = (prep.sc[static_cast<std::size_t>(s)] - pos).norm();
      if (d > p.position_tolerance_mm)
        continue;
      if (best < 0 || d < best_dist) {
        best = s;
        best_dist = d;
      }
    }
    if (best >= 0) {
      used[static_cast<std::size_t>(best)] = 1;
      out.matched_features.emplace_back(m, best);
      residual += best_dist;
      ++count;
    }
  }
  out.score = n_model > 0 ? static_cast<double>(count) / n_model : 0.0;
  out.residual_mm = count > 0 ? residual / count : 0.0;
  *count_out = count;
  return out;
}

/// The closest T2 for one M2 at the roll that brings the prediction onto it.
struct RollHypothesis {
  double roll_rad = 0.0;
  double closeness = 0.0; // normalized description difference, smaller is closer
  int m2 = -1, t2 = -1;
};

/// The best candidate of one M1 task, with its tie-break key.
struct TaskBest {
  int count = -1;
  MatchCandidate candidate;
  /// With several hypotheses: distinct poses, most confirmed features first, at most
  /// params.hypotheses of them.
  std::vector<std::pair<int, MatchCandidate>> alternatives;
};

/// Two poses are the same hypothesis when they agree within the matching tolerances.
bool samePose(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, const MatchingParams& p) {
  if ((a.translation() - b.translation()).norm() > p.position_tolerance_mm)
    return false;
  return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle() <=
         p.orientation_tolerance_rad;
}

/// Adds (count, c) to `list` (sorted by count, descending, stable) unless an equal pose with at
/// least as many features is there; an equal pose with fewer is replaced. Keeps at most `k`.
void keepAlternative(std::vector<std::pair<int, MatchCandidate>>& list, int count, MatchCandidate c,
                     std::size_t k, const MatchingParams& p) {
  for (auto it = list.begin(); it != list.end(); ++it)
    if (samePose(it->second.T_scene_model, c.T_scene_model, p)) {
      if (it->first >= count)
        return;
      list.erase(it);
      break;
    }
  auto pos = std::find_if(list.begin(), list.end(), [&](const auto& e) { return e.first < count; });
  list.insert(pos, {count, std::move(c)});
  if (list.size() > k)
    list.resize(k);
}

/// Refinement on all confirmed pairs: the two seed pairs fix the pose, the others average out
/// the errors of individual features. Kept only while it does not lose confirmations.
MatchCandidate refineOnConfirmedPairs(const Prepared& prep, const FeatureList& model,
                                      const FeatureList& scene, MatchCandidate best) {
  for (int iteration = 0; iteration < 3 && best.matched_features.size() >= 2; ++iteration) {
    const Eigen::Isometry3d T = refineOnFeatureGeometry(
        model, scene, best.matched_features,
        fitFeaturePairs(model, scene, best.matched_features, best.T_scene_model));
    int count = 0;
    MatchCandidate refined = scoreWithBound(prep, T, 0, &count);
    if (refined.matched_features.size() < best.matched_features.size())
      break;
    refined.seed1 = best.seed1;
    refined.seed2 = best.seed2;
    const bool same_pairs = refined.matched_features == best.matched_features;
    best = std::move(refined);
    if (same_pairs)
      break;
  }
  return best;
}

class Search {
public:
  explicit Search(const Prepared& prep) : m_prep(prep) {}

  TaskBest runM1(int i) {
    const auto& p = m_prep.params;
    const auto n_scene = static_cast<int>(m_prep.scene.size());
    const auto n_model = static_cast<int>(m_prep.model.size());
    const Feature& m1 = m_prep.model[static_cast<std::size_t>(i)];
    const double step_rad = std::max(p.roll_step_deg, 0.01) * M_PI / 180.0;
    const bool pooled = p.pool_size > 0;
    const auto k_alternatives =
        static_cast<std::size_t>(pooled ? p.pool_size : std::max(1, p.hypotheses));
    const bool several = k_alternatives > 1;
    TaskBest best;
    for (int j = 0; j < n_scene; ++j) {
      // A task with a lower M1 already confirmed every model feature: nothing here can win.
      if (i > m_perfect_m1.load(std::memory_order_relaxed))
        return best;
      if (!isAvailable(m_prep.available, j) ||
          !descriptorsAgree(m1, m_prep.scene[static_cast<std::size_t>(j)], p))
        continue;
      for (int sign : {1, -1}) {
        const Vec3 axis = sign * m_prep.sd[static_cast<std::size_t>(j)];
        const Eigen::Matrix3d R1 = rotationBetween(m_prep.md[static_cast<std::size_t>(i)], axis);
        std::map<long, RollHypothesis> bins;
        for (int k = 0; k < n_model; ++k) {
          if (k == i)
            continue;
          if (auto h = bestT2(i, j, k, axis, R1)) {
            const double wrapped = std::fmod(h->roll_rad + 4.0 * M_PI, 2.0 * M_PI);
            const long bin = static_cast<long>(std::floor(wrapped / step_rad));
            auto it = bins.find(bin);
            if (it == bins.end() || h->closeness < it->second.closeness)
              bins[bin] = *h;
          }
        }
        for (const auto& [bin, h] : bins) {
          Eigen::Isometry3d guess = Eigen::Isometry3d::Identity();
          guess.linear() = Eigen::AngleAxisd(h.roll_rad, axis).toRotationMatrix() * R1;
          guess.translation() = m_prep.sc[static_cast<std::size_t>(j)] -
                                guess.linear() * m_prep.mc[static_cast<std::size_t>(i)];
          const Eigen::Isometry3d T =
              fitFeaturePairs(m_prep.model, m_prep.scene, {{i, j}, {h.m2, h.t2}}, guess);
          // Later hypotheses of this task lose ties; other tasks' winners only prune strictly.
          // With several hypotheses, poses one feature short of the best stay in the running.
          const int global = m_global_best.load(std::memory_order_relaxed);
          // Pooled: every instance of a bin counts, so the best one found prunes nothing.
          const int need = pooled    ? m_prep.min_pool_count
                           : several ? std::max(2, global - 1)
                                     : std::max(best.count + 1, global);
          int count = 0;
          MatchCandidate c = scoreWithBound(m_prep, T, need, &count);
          if (count < 0 || (!several && count <= best.count))
            continue;
          c.seed1 = {i, j};
          c.seed2 = {h.m2, h.t2};
          raiseGlobal(count);
          if (several) {
            if (count > best.count) {
              best.count = count;
              best.candidate = c;
            }
            keepAlternative(best.alternatives, count, std::move(c), k_alternatives, p);
            continue;
          }
          best.count = count;
          best.candidate = std::move(c);
          if (count == n_model) {
            lowerPerfect(i);
            return best;
          }
        }
      }
    }
    return best;
  }

private:
  /// The closest scene feature on the toroid of M2 around T1 (Figure 3.5 d-f), if any.
  std::optional<RollHypothesis> bestT2(int i, int j, int k, const Vec3& axis,
                                       const Eigen::Matrix3d& R1) const {
    const auto& p = m_prep.params;
    const auto su = [](int x) { return static_cast<std::size_t>(x); };
    const Vec3 v = R1 * (m_prep.mc[su(k)] - m_prep.mc[su(i)]);
    const double h = v.dot(axis);
    const Vec3 v_perp = v - h * axis;
    const double rho = v_perp.norm();
    const Vec3 o = R1 * m_prep.md[su(k)];
    const Vec3 o_perp = o - o.dot(axis) * axis;
    const bool position_sets_roll = rho >= p.position_tolerance_mm;
    // Parallel to M1 and on its axis: every roll predicts the same T2, so M2 cannot fix the roll
    // (the thesis's ambiguity of two parallel lines). With several verified hypotheses (beyond
    // the thesis) the pair is still taken at roll 0: for a part turned about that axis (a cup's
    // rim and base circles) any roll is as good, and for others verification judges it.
    const bool roll_free =
        !position_sets_roll && o_perp.norm() < std::sin(p.orientation_tolerance_rad);
    if (roll_free && p.hypotheses <= 1)
      return std::nullopt;
    const double tol_size = sizeTolerance(p, m_prep.model[su(k)].type);
    const double vn = v.norm();
    const auto& shell = m_prep.shells[su(j)];
    auto it = std::lower_bound(shell.begin(), shell.end(),
                               std::make_pair(vn - p.position_tolerance_mm, -1));
    std::optional<RollHypothesis> best;
    for (; it != shell.end() && it->first <= vn + p.position_tolerance_mm; ++it) {
      const int t = it->second;
      if (t == j || !isAvailable(m_prep.available, t) ||
          !descriptorsAgree(m_prep.model[su(k)], m_prep.scene[su(t)], p))
        continue;
      const Vec3 q = m_prep.sc[su(t)] - m_prep.sc[su(j)];
      const double a = q.dot(axis);
      const Vec3 q_perp = q - a * axis;
      if (std::hypot(a - h, q_perp.norm() - rho) > p.position_tolerance_mm)
        continue; // outside the toroid
      double rolls[2];
      int n_rolls = 0;
      const auto signedAngle = [&](const Vec3& from, const Vec3& to) {
        return std::atan2(axis.dot(from.cross(to)), from.dot(to));
      };
      if (roll_free) {
        rolls[n_rolls++] = 0.0;
      } else if (position_sets_roll) {
        rolls[n_rolls++] = signedAngle(v_perp, q_perp);
      } else {
        const Vec3 d = m_prep.sd[su(t)];
        const Vec3 d_perp = d - d.dot(axis) * axis;
        rolls[n_rolls++] = signedAngle(o_perp, d_perp);
        rolls[n_rolls++] = signedAngle(o_perp, -d_perp);
      }
      for (int r = 0; r < n_rolls; ++r) {
        const Eigen::Matrix3d roll = Eigen::AngleAxisd(rolls[r], axis).toRotationMatrix();
        const double dist = (m_prep.sc[su(j)] + roll * v - m_prep.sc[su(t)]).norm();
        const double angle = axisAngle(roll * o, m_prep.sd[su(t)]);
        if (dist > p.position_tolerance_mm || angle > p.orientation_tolerance_rad)
          continue;
        const double size_diff = std::abs(static_cast<double>(m_prep.model[su(k)].size_mm) -
                                          m_prep.scene[su(t)].size_mm);
        const double closeness = dist / std::max(p.position_tolerance_mm, 1e-9) +
                                 angle / std::max(p.orientation_tolerance_rad, 1e-9) +
                                 (tol_size > 0.0 ? size_diff / tol_size : 0.0);
        if (!best || closeness < best->closeness)
          best = RollHypothesis{rolls[r], closeness, k, t};
      }
    }
    return best;
  }

  void raiseGlobal(int count) {
    int cur = m_global_best.load();
    while (count > cur && !m_global_best.compare_exchange_weak(cur, count)) {
    }
  }
  void lowerPerfect(int i) {
    int cur = m_perfect_m1.load();
    while (i < cur && !m_perfect_m1.compare_exchange_weak(cur, i)) {
    }
  }

  const Prepared& m_prep;
  std::atomic<int> m_global_best{0};
  std::atomic<int> m_perfect_m1{INT_MAX};
};

} // namespace

MatchCandidate scoreTransformation(const FeatureList& model, const FeatureList& scene,
                                   const Eigen::Isometry3d& T_scene_model,
                                   const MatchingParams& params,
                                   const std::vector<char>& scene_available) {
  if (!scene_available.empty() && scene_available.size() != scene.size())
    throw Error("scene feature mask has " + std::to_string(scene_available.size()) +
                " entries for " + std::to_string(scene.size()) + " features");
  const Prepared prep(model, scene, params, scene_available, false);
  int count = 0;
  return scoreWithBound(prep, T_scene_model, 0, &count);
}

std::vector<MatchCandidate> refineOnFeatures(const FeatureList& model, const FeatureList& scene,
                                             const std::vector<Eigen::Isometry3d>& T_scene_model,
                                             const MatchingParams& params) {
  const std::vector<char> all;
  const Prepared prep(model, scene, params, all, false);
  std::vector<MatchCandidate> out(T_scene_model.size());
  tbb::parallel_for(std::size_t{0}, out.size(), [&](std::size_t k) {
    int count = 0;
    out[k] = refineOnConfirmedPairs(prep, model, scene,
                                    scoreWithBound(prep, T_scene_model[k], 0, &count));
  });
  return out;
}

std::optional<MatchCandidate>
findBestTransformation(const FeatureList& model, const FeatureList& scene,
                       const MatchingParams& params, const std::vector<char>& scene_available,
                       const ProgressFn& progress, const PoseVerifier& verify) {
  if (!scene_available.empty() && scene_available.size() != scene.size())
    throw Error("scene feature mask has " + std::to_string(scene_available.size()) +
                " entries for " + std::to_string(scene.size()) + " features");
  if (model.size() < 2 || scene.size() < 2)
    return std::nullopt;
  const Prepared prep(model, scene, params, scene_available, true);
  Search search(prep);
  std::vector<TaskBest> results(model.size());
  parallelForWithProgress(model.size(), progress,
                          [&](std::size_t i) { results[i] = search.runM1(static_cast<int>(i)); });
  // Deterministic reduction: the highest count wins, ties go to the lowest M1.
  const TaskBest* winner = nullptr;
  for (const auto& r : results)
    if (r.count > 0 && (!winner || r.count > winner->count))
      winner = &r;
  if (!winner)
    return std::nullopt;
  // Refinement on all confirmed pairs: the two seed pairs fix the pose, the others average out
  // the errors of individual features. Kept only while it does not lose confirmations.
  const auto refine = [&](MatchCandidate best) {
    return refineOnConfirmedPairs(prep, model, scene, std::move(best));
  };
  if (!verify)
    return refine(winner->candidate);
  if (params.hypotheses <= 1) {
    MatchCandidate best = refine(winner->candidate);
    best.coverage = verify(best.T_scene_model);
    return best;
  }
  // Pool the tasks' alternatives in task order (deterministic), keep the distinct poses within
  // one feature of the best, verify each and take the best verified one.
  std::vector<std::pair<int, MatchCandidate>> pool;
  const auto k = static_cast<std::size_t>(params.hypotheses);
  for (const auto& r : results)
    for (const auto& [count, c] : r.alternatives)
      if (count >= winner->count - 1)
        keepAlternative(pool, count, c, k, params);
  std::vector<MatchCandidate> verified(pool.size());
  tbb::parallel_for(std::size_t{0}, pool.size(), [&](std::size_t a) {
    verified[a] = refine(pool[a].second);
    verified[a].coverage = verify(verified[a].T_scene_model);
  });
  std::size_t chosen = 0;
  for (std::size_t a = 1; a < verified.size(); ++a) {
    const auto& c = verified[a];
    const auto& b = verified[chosen];
    if (c.coverage > b.coverage + 1e-9 || (std::abs(c.coverage - b.coverage) <= 1e-9 &&
                                           c.matched_features.size() > b.matched_features.size()))
      chosen = a;
  }
  return verified[chosen];
}

namespace {

/// Best first: by coverage when verified, else by feature score (stable).
std::vector<MatchCandidate> sortedBest(std::vector<MatchCandidate> candidates, bool verified) {
  std::stable_sort(candidates.begin(), candidates.end(),
                   [&](const MatchCandidate& a, const MatchCandidate& b) {
                     return verified ? a.coverage > b.coverage : a.score > b.score;
                   });
  return candidates;
}

/// Pooled multi-instance matching (params.pool_size > 0 with a verifier): one search over all
/// seeds keeps up to pool_size distinct poses, each refined on its features and verified; every
/// pose reaching min_coverage is returned (the caller removes duplicates of one instance).
std::vector<MatchCandidate> matchPooled(const FeatureList& model, const FeatureList& scene,
                                        const MatchingParams& params, const ProgressFn& progress,
                                        const PoseVerifier& verify) {
  std::vector<MatchCandidate> out;
  if (model.size() < 2 || scene.size() < 2)
    return out;
  const std::vector<char> all_available;
  const Prepared prep(model, scene, params, all_available, true);
  Search search(prep);
  const auto n_model = static_cast<int>(model.size());
  std::vector<TaskBest> results(model.size());
  tbb::parallel_for(0, n_model,
                    [&](int i) { results[static_cast<std::size_t>(i)] = search.runM1(i); });
  reportProgress(progress, 0.5);
  std::vector<std::pair<int, MatchCandidate>> pool;
  for (const auto& r : results)
    for (const auto& [count, c] : r.alternatives)
      keepAlternative(pool, count, c, static_cast<std::size_t>(params.pool_size), params);
  std::vector<MatchCandidate> verified(pool.size());
  tbb::parallel_for(std::size_t{0}, pool.size(), [&](std::size_t a) {
    verified[a] = refineOnConfirmedPairs(prep, model, scene, pool[a].second);
    verified[a].coverage = verify(verified[a].T_scene_model);
  });
  for (auto& c : verified)
    if (c.score >= params.score_threshold && c.coverage >= params.min_coverage)
      out.push_back(std::move(c));
  reportProgress(progress, 1.0);
  return out;
}

} // namespace

std::vector<MatchCandidate> matchFeatures(const FeatureList& model, const FeatureList& scene,
                                          const MatchingParams& params, const ProgressFn& progress,
                                          const PoseVerifier& verify) {
  if (verify && params.pool_size > 0)
    return sortedBest(matchPooled(model, scene, params, progress, verify), true);
  std::vector<MatchCandidate> out;
  std::vector<char> available(scene.size(), 1);
  for (int round = 0, rounds = std::max(1, params.max_instances_per_cluster); round < rounds;
       ++round) {
    auto candidate = findBestTransformation(
        model, scene, params, available,
        subProgress(progress, double(round) / rounds, double(round + 1) / rounds), verify);
    if (!candidate || candidate->score < params.score_threshold || candidate->score <= 0.0)
      break;
    for (const auto& [m, s] : candidate->matched_features)
      available[static_cast<std::size_t>(s)] = 0;
    // A pose the points do not confirm is dropped, but its features stay used: they belong to
    // something that is not a good instance, and the next round may find one elsewhere.
    if (verify && candidate->coverage < params.min_coverage)
      continue;
    out.push_back(std::move(*candidate));
  }
  reportProgress(progress, 1.0);
  return sortedBest(std::move(out), static_cast<bool>(verify));
}

} // namespace scanpick::core
