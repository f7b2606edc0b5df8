#pragma once
/// \file ransac.h A first T_target_source from patch correspondences by RANSAC over centroids.
///
/// Minimal samples of 3 correspondences whose pairs are consistent (rigid motions keep distances
/// and angles): the pairwise centroid distances agree between the views,
/// |d_s(i,j) - d_t(i,j)| <= edge_tolerance_m, as do the pairwise normal angles,
/// |angle(n_si, n_sj) - angle(n_ti, n_tj)| <= normal_pair_tolerance_deg, and the source triangle
/// is not thin (its smallest height >= min_triangle_height_m).
///
/// Sampling (`guided_sampling`, default): the consistent pairs are computed once as a
/// compatibility graph, and samples are drawn from its triangles (i uniform, j uniform among the
/// partners of i, k uniform among the common partners of i and j), so every sample is
/// consistent. With few correct associations among many (as on wide baselines) uniform triples
/// almost never pass the checks (the inlier ratio cubed); guided ones are all-inlier with a
/// probability of the order of the inlier ratio. The number of samples adapts to the best model:
/// N = log(1 - confidence) / log(1 - P), P the probability that one draw returns three of its
/// inliers under this sampler (exact for the sampler; thin triangles included), at least
/// min_iterations (guided sampling only), at most max_iterations. As in standard RANSAC this is a stopping heuristic:
/// unlike e^3, P does not grow with the inlier count (a small tight clique of wrong matches can
/// have a larger P than a larger true set among near-miss wrong matches), hence the floor.
/// Without guided sampling, or above max_guided_correspondences (the graph takes n^2 / 8 bytes):
/// uniform triples, checked, P = e^3 (e = inlier ratio).
///
/// A sample gives T in closed form (Eigen::umeyama, no scale) and is scored by its inliers
/// (InlierCriterion), ties broken by the truncated cost sum_i min(d_i^2 / d_max^2, 1) (MSAC). The
/// best model is re-fitted on its inliers (weighted least squares) and the inliers recounted,
/// twice. Single-threaded and deterministic for a seed.
///
/// The best distinct alternative: the best-scoring model among those sampled (with at least
/// min_inliers inliers) that places the source centroids more than twice the inlier distance
/// away from the best model's placement, RMS (rmsDisplacement, pose.h), so that the two cannot
/// both lie within the inlier distance of one pose. It is re-fitted like the best model; the
/// sampled models are kept one per placement (those within the inlier distance of each other
/// count as one). The pipeline's certificate asks whether
/// the chosen pose explains the views better than it (certify_stage.h, uniqueness).
#include <optional>
#include <string>
#include <vector>

#include "gasp/core/pose.h"
#include "gasp/registration/correspondence.h"
#include "gasp/registration/inlier_criterion.h"

namespace gasp {

struct RansacParams {
  InlierCriterion inlier;                  ///< 0.05 m centroid distance, 20 deg normal angle
  double edge_tolerance_m = 0.03;          ///< max |d_s(i,j) - d_t(i,j)| within a sample [m]
  double normal_pair_tolerance_deg = 20.0; ///< max disagreement of a sample's normal angles [deg]
  double min_triangle_height_m = 0.05;     ///< smallest height of a sample's source triangle [m]
  int min_inliers = 8;                     ///< fewer inliers than this: no estimate
  int max_iterations = 10000;              ///< cap on the samples drawn (rejected ones count)
  double confidence = 0.999;               ///< in (0, 1): probability of one all-inlier sample
  unsigned seed = 1;                       ///< std::mt19937 seed
  bool guided_sampling = true;             ///< samples from the compatibility graph (see above)
  int min_iterations = 200;                ///< guided sampling: samples drawn at least (if max_iterations allows)
  /// Above: uniform sampling. The graph costs n^2 / 8 bytes and n^2 / 2 tests, and with thousands
  /// of matches (dense SIFT) its triangles are dense with wrong ones, so its stopping
  /// probability stays small and every search runs to max_iterations, which takes seconds.
  int max_guided_correspondences = 1500;
};

/// Throws gasp::Error naming the first invalid parameter.
void validate(const RansacParams& params);

struct RansacResult {
  bool success = false;  ///< a model with >= min_inliers inliers was found
  Isometry3 T_target_source = Isometry3::Identity();
  std::vector<int> inliers;   ///< ascending indices into the correspondences
  /// The best distinct alternative (above); empty when RANSAC sampled none with min_inliers.
  std::optional<Isometry3> alternative_T_target_source;
  std::vector<int> alternative_inliers;  ///< ascending indices into the correspondences
  int iterations = 0;         ///< samples drawn
  int rejected_samples = 0;   ///< of those, rejected by the consistency checks before fitting
  std::string reason;         ///< why there is no estimate
};

RansacResult ransacPose(const std::vector<PatchCorrespondence>& correspondences, const RansacParams& params = {});

}  // namespace gasp
