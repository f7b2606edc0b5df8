// Pairs of a simulated LiDAR sequence registered with no prior (registerRangeScans), scored
// against the exact ground truth: pairs 1, 5 and 10 sweeps apart by default.
//   build/ci/bin/gasp-simulate --sensor lidar16 --frames 60 --rate 10 --out /tmp/lidar16
//   build/ci/bin/bench_lidar_sequence /tmp/lidar16 [--skips 1,5,10] [--threads 2] [--pair I,J]
//       [--method gasp|fpfh] [--shares] [--nees] [--dense-step N] [--params FILE]
// --params FILE (gasp): the params file's pair sections made a LiDAR's by its lidar section
// (lidarPairParams), as gasp-odometry and the MRPT classes take them; the defaults otherwise.
// --shares (gasp): a line per claimed pose with the share of the source's patches that land on
// target patches and of those verified, its inliers and its free-space test's violation ratios
// (both ways) and occluded share (the leads for a rule against wrong poses).
// --nees (gasp): a line per claimed pose with its NEES against the truth under its edge
// information (pose_consistency.h: chi-square with 6 degrees of freedom if the information is
// right; 95 % below 12.59).
// --slides (gasp): for each claimed pose refined on the returns, and for each refused one after
// the returns' rounds from it, its returns' cost above the lowest of its slide profile
// (slideProfile) and where that lies (study 2026-11-30 section 5).
// --method fpfh: PCL FPFH + RANSAC on the returns (gasp::baselines, when built), the same scoring.
// --pair I,J: only that pair, with the pipeline's verdicts (inliers, support, certificate), the
// claimed pose's NEES against the truth (pose_consistency.h), or for a refused pose what the
// returns' rounds (stage 7) would have made of it and what the free-space test says of that; the
// returns' cost with the pose slid along its weakest translation (slideProfile), the returns'
// rounds restarted 0.1, 0.15 (the basin test's) and 0.2 m either side along it (printBasin), the
// distinct surfaces fixing
// it (surfacesAlongWeakest), the rounds on the source's odd and even rows alone
// (printSplitHalves), and association against the truth (printAssociationOracle: true partners,
// true associations, the partner's edit-distance rank); for a claimed pose, the returns' rounds
// started at the truth (is their cost's minimum off it?), the truth's Gauss-Newton step split by
// the target patch the terms lie on, and the claimed error's NEES under the rounds' information,
// a per-term and a per-surface (cluster-robust) covariance (printTruthStart).
// --dense-step N (gasp): the dense rounds sample at least every N-th binned cell each way (their
// step is the larger of N and the sample spacing's, lidar.dense_sample_spacing_deg; every cell
// takes --params with lidar: {dense_sample_spacing_deg: 0}).
// --deskew-truth: each sweep first carried to its start pose (deskewSweep) with the truth's
// velocity to the next sweep: sweeps simulated with --sweep-motion as a deskew with an exact
// velocity would leave them (the odometry deskews with its own last step's).
// A claimed pose within 5 cm / 0.5 deg of the truth is right (the bound), one within
// 20 cm / 5 deg is coarse (a start ICP converges from), any other claimed pose is wrong; the rest
// give no estimate; in brackets, those of them whose sweeps share at least 30 % of their depth
// under the truth (sharedDepth; under that, no estimate is the right answer). Prints one table
// row per skip.
#include <Eigen/Eigenvalues>
#include <tbb/global_control.h>

#include <mrpt/obs/CObservation.h>
#include <mrpt/obs/CObservationRotatingScan.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/core/tum_trajectory.h"
#include "gasp/eval/pose_consistency.h"
#include "gasp/params/params_file.h"
#include "gasp/pipeline/associate_stage.h"
#include "gasp/pipeline/certify_stage.h"
#include "gasp/pipeline/ground_search.h"
#include "gasp/pipeline/range_view.h"
#include "gasp/pipeline/returns_stage.h"
#include "gasp/pipeline/visibility_check.h"
#include "gasp/rawlog/range_scan.h"
#include "gasp/rawlog/rawlog_objects.h"
#ifdef GASP_HAVE_BASELINES
#include "gasp/baselines/baseline_registration.h"
#endif

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

std::vector<gasp::RangeScan> readSweeps(const std::string& path) {
  std::vector<gasp::RangeScan> sweeps;
  gasp::RawlogObjects objects(path);
  while (const auto object = objects.next())
    if (const auto obs = std::dynamic_pointer_cast<mrpt::obs::CObservation>(object); obs && gasp::isSweepObservation(*obs))
      sweeps.push_back(gasp::rangeScanFrom(*obs));
  if (sweeps.empty()) throw gasp::Error("'" + path + "' holds no LiDAR sweep (rotating scan, Velodyne scan or point cloud)");
  return sweeps;
}

/// Of the source's patches at the claimed pose: how many land on a target patch, and how many
/// were verified (guided associations).
struct PatchShares {
  std::size_t source = 0, landing = 0, verified = 0;
  int inliers = 0;
  double violation = 0.0, violation_lesser = 0.0, occluded = 0.0;  ///< the free-space test of the pose
};

PatchShares patchShares(const gasp::RangePairResult& r, const gasp::RangeScan& source, const gasp::RangeScan& target) {
  const gasp::DepthView va = gasp::makeRangeView(source, gasp::lidarSuperpixelParams());
  const gasp::DepthView vb = gasp::makeRangeView(target, gasp::lidarSuperpixelParams());
  const auto [ps, pt] = gasp::viewsOf(r.pair, va, vb);
  PatchShares s;
  s.source = ps->segmentation.patches.size();
  s.verified = r.pair.verified.size();
  s.inliers = r.pair.pose.num_inliers;
  s.violation = r.pair.visibility.violation_ratio;
  s.violation_lesser = r.pair.visibility.violation_ratio_lesser;
  s.occluded = r.pair.visibility.occluded_ratio;
  for (const auto& patch : ps->segmentation.patches) {
    double u = 0, v = 0;
    if (!pt->projection.project(r.pair.pose.T_target_source * patch.centroid, u, v)) continue;
    const int ui = static_cast<int>(std::lround(u)), vi = static_cast<int>(std::lround(v));
    if (ui < 0 || vi < 0 || ui >= pt->segmentation.labels.cols || vi >= pt->segmentation.labels.rows) continue;
    s.landing += pt->segmentation.labels.at<int>(vi, ui) >= 0 ? 1 : 0;
  }
  return s;
}

/// The share of both sweeps' depth the other sees at the same place under the true pose: the
/// free-space test's consistent samples (the LiDAR's gate, every cell) over both views' valid
/// cells. Under 30 % "no estimate" is the right answer (docs/evaluation.md "Failures").
double sharedDepth(const gasp::RangeScan& source, const gasp::RangeScan& target, const gasp::Isometry3& T_true,
                   const gasp::PairParams& params) {
  const gasp::DepthView va = gasp::makeRangeView(source, params.segment);
  const gasp::DepthView vb = gasp::makeRangeView(target, params.segment);
  gasp::VisibilityCheckParams every = params.certify.visibility;
  every.pixel_step = 1;
  const gasp::VisibilityCheck c = gasp::checkVisibility(va, vb, T_true, every);
  const int valid = cv::countNonZero(va.depth_m > 0) + cv::countNonZero(vb.depth_m > 0);
  return valid > 0 ? static_cast<double>(c.consistent) / valid : 0.0;
}

/// --pair: the returns' rounds from `start` on the source's even rows and on its odd rows alone
/// (two sets of returns that share no measurement), each half's error against the truth, and
/// their disagreement against the information both claim: xi^T (C_even + C_odd)^-1 xi,
/// chi-square with 6 degrees of freedom when the claimed information is right.
void printSplitHalves(const gasp::RangeScan& source, const gasp::DepthView& vb, const gasp::Isometry3& start,
                      const gasp::Isometry3& T_true, const gasp::PairParams& params) {
  std::array<gasp::RegistrationResult, 2> half;
  for (int parity = 0; parity < 2; ++parity) {
    gasp::RangeScan h = source;
    h.range_m = source.range_m.clone();
    for (int r = parity; r < h.range_m.rows; r += 2) h.range_m.row(r).setTo(0.0f);
    const gasp::SweepReturns returns(h, params.returns);
    half[static_cast<std::size_t>(parity)] = gasp::refineOnReturns(returns, *vb.returns, start, params.returns, params.refine.solver,
                                                                   vb.superpixels.max_incidence_deg);
  }
  std::printf("  split halves (odd rows, even rows):");
  for (const auto& q : half) {
    const gasp::Isometry3 e = T_true.inverse() * q.T_target_source;
    std::printf(" success %d error %.2f cm %.3f deg;", q.success, 100.0 * e.translation().norm(),
                Eigen::AngleAxisd(e.linear()).angle() * 180.0 / M_PI);
  }
  if (half[0].success && half[1].success && half[0].information.determinant() > 0.0 && half[1].information.determinant() > 0.0) {
    const gasp::eval::Vector6 xi = gasp::eval::leftPerturbation(half[0].T_target_source, half[1].T_target_source);
    const gasp::Matrix6d C = half[0].information.inverse() + half[1].information.inverse();
    std::printf(" disagreement %.1f (translation %.2f cm)", xi.dot(C.ldlt().solve(xi)), 100.0 * xi.head<3>().norm());
  }
  std::printf("\n");
}

/// The label of the target patch whose binned cell a point (target frame) falls in; -1 for none.
int patchLabelAt(const gasp::DepthView& view, const Eigen::Vector3d& q) {
  double u = 0, v = 0;
  if (!view.projection.project(q, u, v)) return -1;
  const int ui = static_cast<int>(std::lround(u)), vi = static_cast<int>(std::lround(v));
  if (ui < 0 || vi < 0 || ui >= view.segmentation.labels.cols || vi >= view.segmentation.labels.rows) return -1;
  return view.segmentation.labels.at<int>(vi, ui);
}

/// Every return of a sweep (sensor frame).
std::vector<Eigen::Vector3d> returnPoints(const gasp::SweepReturns& sweep) {
  std::vector<Eigen::Vector3d> points;
  for (int r = 0; r < sweep.rows(); ++r)
    for (int c = 0; c < sweep.cols(); ++c)
      if (const Eigen::Vector3d& p = sweep.point(r, c); p.allFinite()) points.push_back(p);
  return points;
}

/// How many distinct surfaces fix the weakest translation of a returns' pose: the returns' last-gate
/// terms at the pose grouped by the target patch their plane point lies in (the binned target
/// view's labels), each group weighing (n . d)^2 summed over its terms for the weakest direction
/// d of the translation information; the effective count (sum w)^2 / sum w^2, and the largest
/// group's share.
struct SurfaceCount {
  double effective = 0.0, largest_share = 0.0;
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();
};
SurfaceCount surfacesAlongWeakest(const gasp::DepthView& va, const gasp::DepthView& vb, const gasp::RegistrationResult& pose,
                                  const gasp::PairParams& params) {
  SurfaceCount out;
  if (!va.returns || !vb.returns) return out;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(pose.information.topLeftCorner<3, 3>());
  const Eigen::Vector3d d = eig.eigenvectors().col(0);
  out.direction = d;
  const std::vector<Eigen::Vector3d> points = returnPoints(*va.returns);
  const std::vector<gasp::PointToPlane> terms = gasp::returnTerms(points, *vb.returns, pose.T_target_source, params.returns.gates_m.back(),
                                                                  params.returns.look_up_columns, vb.superpixels.max_incidence_deg);
  std::vector<double> w(vb.segmentation.patches.size() + 1, 0.0);  // the last: no patch
  for (const gasp::PointToPlane& t : terms) {
    const int label = patchLabelAt(vb, t.q_target);
    const double x = t.n_target.dot(d);
    w[label >= 0 ? static_cast<std::size_t>(label) : w.size() - 1] += x * x;
  }
  double sum = 0, sum2 = 0, largest = 0;
  for (double x : w) sum += x, sum2 += x * x, largest = std::max(largest, x);
  if (sum2 > 0) out.effective = sum * sum / sum2, out.largest_share = largest / sum;
  return out;
}

/// --pair: is the returns' cost minimum itself off the truth? The returns' rounds started at the
/// truth, and at the claimed pose a cluster-robust covariance of the returns' terms (the terms
/// grouped by the target patch their plane lies on; Liang & Zeger's sandwich H^-1 (sum_g s_g
/// s_g^T) H^-1) beside the rounds' own J^T J / sigma^2, with the claimed error's NEES under each.
void printTruthStart(const gasp::DepthView& va, const gasp::DepthView& vb, const gasp::RegistrationResult& pose,
                     const gasp::Isometry3& T_true, const gasp::PairParams& params) {
  if (!va.returns || !vb.returns) return;
  const gasp::RegistrationResult q = gasp::refineOnReturns(*va.returns, *vb.returns, T_true, params.returns,
                                                          params.refine.solver, vb.superpixels.max_incidence_deg);
  const gasp::Isometry3 eq = T_true.inverse() * q.T_target_source;
  std::printf("the returns' rounds from the truth: success %d (%s), end %.2f cm %.3f deg off\n", q.success, q.reason.c_str(),
              100.0 * eq.translation().norm(), Eigen::AngleAxisd(eq.linear()).angle() * 180.0 / M_PI);
  const std::vector<Eigen::Vector3d> points = returnPoints(*va.returns);
  for (const auto& [name, T] : {std::pair<const char*, gasp::Isometry3>{"claimed", pose.T_target_source}, {"truth", T_true}}) {
    const std::vector<gasp::PointToPlane> terms = gasp::returnTerms(points, *vb.returns, T, params.returns.gates_m.back(),
                                                                    params.returns.look_up_columns, vb.superpixels.max_incidence_deg);
    const std::size_t groups = vb.segmentation.patches.size() + 1;
    std::vector<gasp::Vector6d> score(groups, gasp::Vector6d::Zero());
    std::vector<int> count(groups, 0);
    std::vector<double> mean_r(groups, 0.0), mean_inc(groups, 0.0), mean_d(groups, 0.0);
    std::vector<Eigen::Vector3d> mean_n(groups, Eigen::Vector3d::Zero()), mean_q(groups, Eigen::Vector3d::Zero());
    gasp::Matrix6d H = gasp::Matrix6d::Zero(), hc0 = gasp::Matrix6d::Zero();
    const bool at_truth = std::strcmp(name, "truth") == 0;
    for (const gasp::PointToPlane& t : terms) {
      const Eigen::Vector3d p = T * t.p_source;
      const double r = t.n_target.dot(p - t.q_target);
      const double w = t.weight * gasp::robustWeight(params.refine.solver, r);  // as the rounds weigh the term
      gasp::Vector6d J;
      J << t.n_target, p.cross(t.n_target);
      H += w * J * J.transpose();
      const gasp::Vector6d s = w * r * J;
      hc0 += s * s.transpose();
      const int label = patchLabelAt(vb, t.q_target);
      const std::size_t g = label >= 0 ? static_cast<std::size_t>(label) : groups - 1;
      score[g] += s, ++count[g];
      if (at_truth) {
        mean_r[g] += r, mean_n[g] += t.n_target, mean_q[g] += t.q_target;
        const Eigen::Vector3d ray = t.q_target.normalized();
        mean_inc[g] += std::acos(std::min(1.0, std::abs(ray.dot(t.n_target)))) * 180.0 / M_PI;
        mean_d[g] += (p - t.q_target).norm();
      }
    }
    if (at_truth) {  // which surfaces pull the truth towards the claimed pose
      gasp::Vector6d g_all = gasp::Vector6d::Zero();
      for (const gasp::Vector6d& y : score) g_all += y;
      const Eigen::LDLT<gasp::Matrix6d> H_ldlt(H);
      const gasp::Vector6d step = -H_ldlt.solve(g_all);  // Gauss-Newton step from the truth
      std::printf("  Gauss-Newton step from the truth: t (%.2f, %.2f, %.2f) cm, r (%.3f, %.3f, %.3f) deg\n", 100 * step(0),
                  100 * step(1), 100 * step(2), step(3) * 180 / M_PI, step(4) * 180 / M_PI, step(5) * 180 / M_PI);
      std::vector<std::pair<double, std::size_t>> pull;
      for (std::size_t g = 0; g < groups; ++g)
        if (count[g] > 0) pull.push_back({-H_ldlt.solve(score[g]).head<3>().dot(step.head<3>().normalized()), g});
      std::sort(pull.begin(), pull.end(), [](auto& x, auto& y) { return std::abs(x.first) > std::abs(y.first); });
      for (std::size_t k = 0; k < std::min<std::size_t>(10, pull.size()); ++k) {
        const std::size_t g = pull[k].second;
        const double n = count[g];
        const Eigen::Vector3d nn = (mean_n[g] / n).normalized(), qq = mean_q[g] / n;
        std::printf("    surface %zu: %d terms, pulls %.2f cm along the step, mean residual %.2f cm, normal (%.2f, %.2f, %.2f), "
                    "at (%.2f, %.2f, %.2f), incidence %.0f deg, point-to-return %.1f cm\n",
                    g, count[g], 100 * pull[k].first, 100 * mean_r[g] / n, nn.x(), nn.y(), nn.z(), qq.x(), qq.y(), qq.z(),
                    mean_inc[g] / n, 100 * mean_d[g] / n);
      }
    }
    gasp::Matrix6d meat = gasp::Matrix6d::Zero();
    int used = 0;
    for (std::size_t g = 0; g < groups; ++g)
      if (count[g] > 0) meat += score[g] * score[g].transpose(), ++used;
    const gasp::Matrix6d Hinv = H.inverse();
    const gasp::Matrix6d C_cluster = Hinv * meat * Hinv, C_hc0 = Hinv * hc0 * Hinv;
    const double sigma = params.refine.solver.noise_sigma_m;
    const gasp::Matrix6d C_model = Hinv * sigma * sigma;
    const gasp::eval::Vector6 xi = gasp::eval::leftPerturbation(pose.T_target_source, T_true);
    auto nees = [&](const gasp::Matrix6d& C) { return xi.dot(C.ldlt().solve(xi)); };
    auto tstd = [&](const gasp::Matrix6d& C) {
      return 100.0 * std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(C.topLeftCorner<3, 3>()).eigenvalues()(2));
    };
    auto rstd = [&](const gasp::Matrix6d& C) {
      return 180.0 / M_PI * std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(C.bottomRightCorner<3, 3>()).eigenvalues()(2));
    };
    std::printf("  at the %s pose: %zu terms on %d surfaces; largest translation sigma / rotation sigma and the claimed "
                "error's NEES: model %.2f cm %.3f deg %.1f, per term %.2f cm %.3f deg %.1f, per surface %.2f cm %.3f deg %.1f\n",
                name, terms.size(), used, tstd(C_model), rstd(C_model), nees(C_model), tstd(C_hc0), rstd(C_hc0), nees(C_hc0),
                tstd(C_cluster), rstd(C_cluster), nees(C_cluster));
  }
}

/// --pair: the returns' rounds again from the pose moved +-`offset_m` along its weakest translation
/// (the largest axis of the translation's covariance, as returnsBasin takes it): how far from it
/// each ends, along that direction and in all.
void printBasin(const gasp::DepthView& va, const gasp::DepthView& vb, const gasp::RegistrationResult& pose,
                const gasp::Isometry3& T_true, const gasp::PairParams& params, double offset_m) {
  const std::optional<Eigen::Vector3d> weakest = gasp::weakestTranslation(pose.information);
  if (!weakest) return;
  const Eigen::Vector3d d = *weakest;
  std::printf("  from %.2f m either side along (%.2f, %.2f, %.2f):", offset_m, d.x(), d.y(), d.z());
  for (const double s : {-offset_m, offset_m}) {
    const gasp::Isometry3 start = Eigen::Translation3d(s * d) * pose.T_target_source;
    const gasp::RegistrationResult q = gasp::refineOnReturns(*va.returns, *vb.returns, start, params.returns,
                                                            params.refine.solver, vb.superpixels.max_incidence_deg);
    const Eigen::Vector3d t = q.T_target_source.translation() - pose.T_target_source.translation();
    const gasp::Isometry3 e = T_true.inverse() * q.T_target_source;
    std::printf(" success %d, ends %.2f cm along it (%.2f cm in all; error %.2f cm);", q.success, 100.0 * t.dot(d),
                100.0 * t.norm(), 100.0 * e.translation().norm());
  }
  std::printf("\n");
}

void printReturnsFreeSpace(const gasp::DepthView& va, const gasp::DepthView& vb, const gasp::Isometry3& T, const char* which,
                           const gasp::PairParams& params) {
  const gasp::VisibilityCheck c = gasp::returnsFreeSpace(*va.returns, *vb.returns, T, params.certify.visibility,
                                                         params.refine.solver.noise_sigma_m, vb.superpixels.max_incidence_deg);
  std::printf("  free space on the returns at %s: violations %.3f / %.3f (worse / lesser direction), occluded %.3f, passed %d\n",
              which, c.violation_ratio, c.violation_ratio_lesser, c.occluded_ratio, c.passed);
}

/// --pair: how far association is from the truth. A source patch's true partner is the target
/// patch whose centroid is nearest its own under the true pose, within RANSAC's inlier distance
/// and with normals within 30 deg. Prints how many source patches have one, how many of the
/// mutual and one-way associations are true partners, and, over every patch with a partner, the
/// rank of its partner's normalised edit distance among all target patches (exhaustive search).
void printAssociationOracle(const gasp::DepthView& va, const gasp::DepthView& vb, const gasp::Isometry3& T_true,
                            const gasp::PairParams& params) {
  const gasp::AssociatedViews a = gasp::associate(va, vb, params.associate);
  const double gate = params.hypothesise.pose.ransac.inlier.distance_m;
  const auto& S = a.source_patches;
  const auto& Tp = a.target_patches;
  std::vector<int> partner(S.size(), -1);
  int with_partner = 0;
  for (std::size_t s = 0; s < S.size(); ++s) {
    if (!gasp::isUsable(S[s]) || a.source_features[s].empty()) continue;
    const Eigen::Vector3d c = T_true * S[s].centroid, n = T_true.linear() * S[s].normal.normalized();
    double best = gate;
    for (std::size_t t = 0; t < Tp.size(); ++t) {
      if (!gasp::isUsable(Tp[t]) || a.target_features[t].empty()) continue;
      const double d = (Tp[t].centroid - c).norm();
      if (d <= best && n.dot(Tp[t].normal.normalized()) >= std::cos(30.0 * M_PI / 180.0)) best = d, partner[s] = static_cast<int>(t);
    }
    with_partner += partner[s] >= 0 ? 1 : 0;
  }
  auto right = [&](const std::vector<gasp::PatchAssociation>& v) {
    int n = 0;
    for (const auto& x : v) n += partner[static_cast<std::size_t>(x.a)] == x.b ? 1 : 0;
    return n;
  };
  std::printf("association against the truth: %d of %zu source patches have a true partner (centroid within %.2f m); "
              "mutual associations true %d of %zu, one-way %d of %zu\n",
              with_partner, S.size(), gate, right(a.result.associations), a.result.associations.size(),
              right(a.result.one_way), a.result.one_way.size());
  std::array<int, 5> ranks{};  // 1, 2-5, 6-20, 21-100, beyond
  std::vector<double> d_true;
  int within_lambda = 0, strictly_best = 0;
  gasp::EditDistanceWorkspace ws;
  const double inf = std::numeric_limits<double>::infinity();
  for (std::size_t s = 0; s < S.size(); ++s) {
    if (partner[s] < 0) continue;
    const auto& q = a.source_features[s];
    auto dhat = [&](std::size_t t) {
      const auto& qt = a.target_features[t];
      if (qt.empty()) return inf;
      return gasp::featureSetDistance(q, qt, a.params.match, a.params.costs, inf, ws) / static_cast<double>(q.size() + qt.size());
    };
    const double mine = dhat(static_cast<std::size_t>(partner[s]));
    int better = 0, tied = 0;
    for (std::size_t t = 0; t < Tp.size(); ++t) {
      if (static_cast<int>(t) == partner[s]) continue;
      const double d = dhat(t);
      better += d < mine ? 1 : 0;
      tied += d == mine ? 1 : 0;
    }
    ranks[better == 0 ? 0 : better < 5 ? 1 : better < 20 ? 2 : better < 100 ? 3 : 4] += 1;
    strictly_best += better == 0 && tied == 0 ? 1 : 0;
    d_true.push_back(mine);
    within_lambda += mine <= a.params.lambda ? 1 : 0;
  }
  std::printf("  the true partner's edit distance: median %.3f, within lambda %.2f for %d; its rank 1: %d, 2-5: %d, "
              "6-20: %d, 21-100: %d, beyond: %d (strictly best, no tie: %d)\n",
              median(d_true), a.params.lambda, within_lambda, ranks[0], ranks[1], ranks[2], ranks[3], ranks[4], strictly_best);
}

/// The returns' truncated point-to-plane cost (the last gate, each source return re-associated as
/// the returns' rounds do) with the pose slid along the weakest translation of its information:
/// a pose the returns observe there sits at the bottom of this profile.
constexpr std::array<double, 9> kSlides = {-0.15, -0.1, -0.05, -0.02, 0.0, 0.02, 0.05, 0.1, 0.15};
std::array<double, 9> slideProfile(const gasp::DepthView& va, const gasp::DepthView& vb, const gasp::RegistrationResult& pose,
                                   const gasp::PairParams& params, bool print = true) {
  std::array<double, 9> costs{};
  if (!va.returns || !vb.returns) return costs;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(pose.information.topLeftCorner<3, 3>());
  const Eigen::Vector3d d = eig.eigenvectors().col(0);
  const double gate = params.returns.gates_m.back();
  const std::vector<Eigen::Vector3d> points = returnPoints(*va.returns);
  if (print) std::printf("the returns' cost slid along (%.2f, %.2f, %.2f) [m: cost/terms]:", d.x(), d.y(), d.z());
  for (std::size_t slide = 0; slide < kSlides.size(); ++slide) {
    const double delta = kSlides[slide];
    const gasp::Isometry3 T = Eigen::Translation3d(delta * d) * pose.T_target_source;
    // The returns' rounds' last-gate terms; every return without one counts as the gate.
    const std::vector<gasp::PointToPlane> terms = gasp::returnTerms(points, *vb.returns, T, gate,
                                                                    params.returns.look_up_columns, vb.superpixels.max_incidence_deg);
    double cost = static_cast<double>(points.size() - terms.size());
    for (const gasp::PointToPlane& t : terms) {
      const double dist = t.n_target.dot(T * t.p_source - t.q_target);
      cost += dist * dist / (gate * gate);
    }
    const int n_terms = static_cast<int>(terms.size());
    costs[slide] = cost;
    if (print) std::printf(" %+.2f: %.1f/%d", delta, cost, n_terms);
  }
  if (print) std::printf("\n");
  return costs;
}

/// --slides: the pose's cost above the lowest of its profile, and where that lies [m].
void printSlide(std::size_t i, std::size_t j, const char* kind, const gasp::Isometry3& T, const gasp::Isometry3& T_true,
                const std::array<double, 9>& costs) {
  const gasp::Isometry3 e = T_true.inverse() * T;
  const double e_cm = 100.0 * e.translation().norm(), e_deg = Eigen::AngleAxisd(e.linear()).angle() * 180.0 / M_PI;
  const auto lowest = std::min_element(costs.begin(), costs.end());
  std::printf("slides %zu %zu %s %s %.2f cm %.3f deg: above the lowest %.1f at %+.2f\n", i, j, kind,
              e_cm <= 5.0 && e_deg <= 0.5 ? "right" : e_cm <= 20.0 && e_deg <= 5.0 ? "coarse" : "wrong", e_cm, e_deg,
              costs[4] - *lowest, kSlides[static_cast<std::size_t>(lowest - costs.begin())]);
}

/// The claimed pose of one pair by the method (nullopt for no estimate), and whether stage 8
/// found the sweeps moving and registered them again deskewed.
struct PairOutcome {
  std::optional<gasp::Isometry3> T_target_source;
  bool deskewed = false;
};

PairOutcome registerPair(const gasp::RangeScan& source, const gasp::RangeScan& target, const std::string& method,
                         const gasp::PairParams& params) {
  PairOutcome out;
  if (method == "gasp") {
    const gasp::RangePairResult r = gasp::registerRangeScans(source, target, params);
    if (r.pair.pose.success) out.T_target_source = r.pair.pose.T_target_source;
    out.deskewed = r.pair.sweep_motion.moving;
    return out;
  }
#ifdef GASP_HAVE_BASELINES
  const gasp::baselines::BaselineResult r =
      gasp::baselines::registerSweepsWithBaseline(source, target, gasp::baselines::BaselineMethod::kFpfh);
  if (r.pose.success) out.T_target_source = r.pose.T_target_source;
  return out;
#else
  throw gasp::Error("--method fpfh: built without the baselines (GASP_BUILD_BASELINES=OFF)");
#endif
}

/// The truth's velocity over sweep k (a constant twist in its own frame): the step to the next
/// sweep, or for the last sweep the step before it, in sweep k's axes.
gasp::CameraTwist truthTwist(const gasp::Trajectory& truth, std::size_t k) {
  const std::size_t a = k + 1 < truth.size() ? k : k - 1;
  gasp::CameraTwist twist = gasp::twistBetween(truth[a].T_world_camera, truth[a + 1].T_world_camera,
                                               truth[a + 1].timestamp - truth[a].timestamp);
  if (a != k)
    twist.v_mps = (truth[a].T_world_camera.linear().transpose() * truth[k].T_world_camera.linear()).transpose() * twist.v_mps;
  return twist;
}

}  // namespace

int main(int argc, char** argv) {
  std::string dir;
  std::vector<int> skips = {1, 5, 10};
  int threads = 2;
  int only_i = -1, only_j = -1;
  std::string method = "gasp";
  bool shares = false, nees = false, slides = false, deskew_truth = false;
  gasp::PairParams params = gasp::lidarPairParams();
  std::string params_path;
  int dense_step = 0;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--skips") == 0 && i + 1 < argc) {
      skips.clear();
      std::stringstream list(argv[++i]);
      for (std::string item; std::getline(list, item, ',');) skips.push_back(std::atoi(item.c_str()));
    } else if (std::strcmp(argv[i], "--method") == 0 && i + 1 < argc) {
      method = argv[++i];
      if (method != "gasp" && method != "fpfh") {
        std::fprintf(stderr, "--method: gasp or fpfh\n");
        return 2;
      }
    } else if (std::strcmp(argv[i], "--shares") == 0) {
      shares = true;
    } else if (std::strcmp(argv[i], "--nees") == 0) {
      nees = true;
    } else if (std::strcmp(argv[i], "--deskew-truth") == 0) {
      deskew_truth = true;
    } else if (std::strcmp(argv[i], "--slides") == 0) {
      slides = true;
    } else if (std::strcmp(argv[i], "--pair") == 0 && i + 1 < argc) {
      if (std::sscanf(argv[++i], "%d,%d", &only_i, &only_j) != 2) only_i = -1;
    } else if (std::strcmp(argv[i], "--dense-step") == 0 && i + 1 < argc) {
      dense_step = std::atoi(argv[++i]);
      if (dense_step < 1) {
        std::fprintf(stderr, "--dense-step: a whole number >= 1\n");
        return 2;
      }
    } else if (std::strcmp(argv[i], "--params") == 0 && i + 1 < argc) {
      params_path = argv[++i];
    } else if (std::strcmp(argv[i], "--threads") == 0 && i + 1 < argc) {
      threads = std::max(1, std::atoi(argv[++i]));
    } else if (dir.empty() && argv[i][0] != '-') {
      dir = argv[i];
    } else {
      std::fprintf(stderr, "usage: bench_lidar_sequence DIR [--skips 1,5,10] [--threads N] [--params FILE] [--dense-step N] [--method gasp|fpfh] [--shares] [--nees] [--slides] [--deskew-truth] [--pair I,J]\n");
      return 2;
    }
  }
  if (dir.empty() || std::any_of(skips.begin(), skips.end(), [](int k) { return k < 1; })) {
    std::fprintf(stderr, "usage: bench_lidar_sequence DIR [--skips 1,5,10] [--threads N] [--params FILE] [--dense-step N] [--method gasp|fpfh] [--shares] [--nees] [--slides] [--deskew-truth] [--pair I,J] (skips >= 1)\n");
    return 2;
  }
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  try {
    if (!params_path.empty()) {  // the file's pair sections made a LiDAR's, as gasp-odometry takes them
      const gasp::SlamParams file = gasp::readParamsFile(params_path);
      params = gasp::lidarPairParams(file.lidar, file.odometry.pair);
    }
    if (dense_step > 0) params.refine.pixels.pixel_step = dense_step;
    std::vector<gasp::RangeScan> sweeps = readSweeps(dir + "/lidar.rawlog");
    const gasp::Trajectory truth = gasp::readTumTrajectory(dir + "/lidar_groundtruth.txt");
    if (truth.size() != sweeps.size())
      throw gasp::Error(dir + ": " + std::to_string(sweeps.size()) + " sweeps but " + std::to_string(truth.size()) +
                        " ground-truth poses");
    if (deskew_truth) {  // each sweep carried to its start pose with the truth's velocity to the next sweep
      if (sweeps.size() < 2) throw gasp::Error("--deskew-truth: at least two sweeps");
      for (std::size_t k = 0; k < sweeps.size(); ++k) sweeps[k] = gasp::deskewSweep(sweeps[k], truthTwist(truth, k));
    }
    std::printf("%s (%s): %zu sweeps of %s, %zu returns each on average\n\n", dir.c_str(), method.c_str(), sweeps.size(),
                sweeps.front().model.c_str(), [&] {
                  std::size_t n = 0;
                  for (const auto& s : sweeps) n += s.returnCount();
                  return n / sweeps.size();
                }());
    if (only_i >= 0) {
      if (only_i >= static_cast<int>(sweeps.size()) || only_j < 0 || only_j >= static_cast<int>(sweeps.size()))
        throw gasp::Error("--pair: sweeps 0 to " + std::to_string(sweeps.size() - 1));
      const auto i = static_cast<std::size_t>(only_i), j = static_cast<std::size_t>(only_j);
      const gasp::RangePairResult r = gasp::registerRangeScans(sweeps[i], sweeps[j], params);
      const gasp::Isometry3 T_true = truth[j].T_world_camera.inverse() * truth[i].T_world_camera;
      const gasp::Isometry3 e = T_true.inverse() * r.pair.pose.T_target_source;
      // The pair's views again, segmented once for the diagnostics below.
      const gasp::DepthView va = gasp::makeRangeView(sweeps[i], params.segment, params.returns);
      const gasp::DepthView vb = gasp::makeRangeView(sweeps[j], params.segment, params.returns);
      std::printf("sweeps %zu -> %zu: success %d (%s), error %.2f cm %.3f deg\n", i, j, r.pair.pose.success,
                  r.pair.pose.reason.c_str(), 100.0 * e.translation().norm(), Eigen::AngleAxisd(e.linear()).angle() * 180.0 / M_PI);
      std::printf("associations %zu, inliers %d, guided support %d, dense terms %d, uniqueness log-ratio %.2f, "
                  "visibility violations %.3f / %.3f, occluded %.3f, returns refined %d (%s)\n",
                  r.pair.association.associations.size(), r.pair.pose.num_inliers, r.pair.guided_support, r.pair.dense_terms,
                  r.pair.uniqueness_log_ratio, r.pair.visibility.violation_ratio, r.pair.visibility.violation_ratio_lesser, r.pair.visibility.occluded_ratio, r.pair.returns_refined, r.pair.returns_reason.c_str());
      {  // stage 8: the sweeps' motion against the truth's velocity over each sweep
        const gasp::SweepMotion& m = r.pair.sweep_motion;
        const gasp::CameraTwist ts = truthTwist(truth, i), tt = truthTwist(truth, j);
        std::printf("sweep motion: estimated %d moving %d (%s) score F %.2f (bound %.2f, %d sectors), %d terms rms %.2f cm, %.0f ms\n"
                    "  source v (%.3f %.3f %.3f) w (%.3f %.3f %.3f), truth v (%.3f %.3f %.3f) w (%.3f %.3f %.3f)\n"
                    "  target v (%.3f %.3f %.3f) w (%.3f %.3f %.3f), truth v (%.3f %.3f %.3f) w (%.3f %.3f %.3f)\n",
                    m.estimated, m.moving, m.reason.c_str(), m.score_f, m.score_bound, m.sectors, m.terms, 100.0 * m.rms_residual_m, m.ms,
                    m.source_twist.v_mps.x(), m.source_twist.v_mps.y(), m.source_twist.v_mps.z(), m.source_twist.w_radps.x(),
                    m.source_twist.w_radps.y(), m.source_twist.w_radps.z(), ts.v_mps.x(), ts.v_mps.y(), ts.v_mps.z(),
                    ts.w_radps.x(), ts.w_radps.y(), ts.w_radps.z(), m.target_twist.v_mps.x(), m.target_twist.v_mps.y(),
                    m.target_twist.v_mps.z(), m.target_twist.w_radps.x(), m.target_twist.w_radps.y(),
                    m.target_twist.w_radps.z(), tt.v_mps.x(), tt.v_mps.y(), tt.v_mps.z(), tt.w_radps.x(), tt.w_radps.y(),
                    tt.w_radps.z());
        const gasp::Isometry3 em = T_true.inverse() * m.T_target_source;
        std::printf("  its pose: error %.2f cm %.3f deg (t %.2f %.2f %.2f cm)\n", 100.0 * em.translation().norm(),
                    Eigen::AngleAxisd(em.linear()).angle() * 180.0 / M_PI, 100.0 * em.translation().x(),
                    100.0 * em.translation().y(), 100.0 * em.translation().z());
      }
      {  // the ground search on its own (ground_search.h), whether or not the pipeline ran it
        const gasp::GroundSearchResult g = gasp::groundSearch(*va.returns, *vb.returns, params.ground_search);
        const gasp::Isometry3 eg = T_true.inverse() * g.T_target_source;
        std::printf("ground search: found %d (%s) cells %d/%d score %.3f error %.2f cm %.3f deg, %.0f ms", g.found, g.reason.c_str(),
                    g.source_cells, g.target_cells, g.score, 100.0 * eg.translation().norm(),
                    Eigen::AngleAxisd(eg.linear()).angle() * 180.0 / M_PI, g.ms);
        if (g.runner_up) {
          const gasp::Isometry3 e2 = T_true.inverse() * *g.runner_up;
          std::printf("; runner-up score %.3f error %.2f cm %.3f deg", g.runner_up_score, 100.0 * e2.translation().norm(),
                      Eigen::AngleAxisd(e2.linear()).angle() * 180.0 / M_PI);
        }
        std::printf("; score at the truth %.3f\n", gasp::groundSearchScore(*va.returns, *vb.returns, T_true, params.ground_search));
        if (g.found) {
          const gasp::RegistrationResult q = gasp::refineOnReturns(*va.returns, *vb.returns, g.T_target_source,
                                                                  params.returns, params.refine.solver, vb.superpixels.max_incidence_deg);
          const gasp::Isometry3 eq = T_true.inverse() * q.T_target_source;
          std::printf("  the returns' rounds from it: success %d (%s) error %.2f cm %.3f deg\n", q.success, q.reason.c_str(),
                      100.0 * eq.translation().norm(), Eigen::AngleAxisd(eq.linear()).angle() * 180.0 / M_PI);
        }
      }
      if (!r.pair.pose.success && r.pair.dense_rounds_run > 0) {  // would the returns' rounds have found the pose from the refused one?
        const gasp::RegistrationResult q = gasp::refineOnReturns(*va.returns, *vb.returns, r.pair.pose.T_target_source,
                                                                params.returns, params.refine.solver, vb.superpixels.max_incidence_deg);
        const gasp::Isometry3 eq = T_true.inverse() * q.T_target_source;
        std::printf("the returns' rounds from the refused pose: success %d, degenerate %d (%s), error %.2f cm %.3f deg, "
                    "information eigenvalues", q.success, q.degenerate,
                    q.reason.c_str(), 100.0 * eq.translation().norm(), Eigen::AngleAxisd(eq.linear()).angle() * 180.0 / M_PI);
        for (int k = 0; k < 6; ++k) std::printf(" %.3g", q.information_eigenvalues(k));
        std::printf("\n");
        printSplitHalves(sweeps[i], vb, r.pair.pose.T_target_source, T_true, params);
        printReturnsFreeSpace(va, vb, r.pair.pose.T_target_source, "the refused pose", params);
        if (q.success) printReturnsFreeSpace(va, vb, q.T_target_source, "the returns' pose from it", params);
        printReturnsFreeSpace(va, vb, T_true, "the truth", params);
        if (q.success) {  // what the certificate's free-space test says of that pose
          const gasp::VisibilityCheck c = gasp::freeSpaceTest(va, vb, params.certify, false)(q.T_target_source);
          std::printf("  its free-space test: passed %d, violations %.3f / %.3f, occluded %.3f, consistent %d (%s)\n", c.passed,
                      c.violation_ratio, c.violation_ratio_lesser, c.occluded_ratio, c.consistent, c.reason.c_str());
        }
        if (q.success) {
          slideProfile(va, vb, q, params);
          const SurfaceCount n = surfacesAlongWeakest(va, vb, q, params);
          std::printf("  surfaces along the weakest translation (%.2f, %.2f, %.2f): effective %.1f, largest share %.2f\n",
                      n.direction.x(), n.direction.y(), n.direction.z(), n.effective, n.largest_share);
          for (const double offset : {0.1, params.returns.basin_offset_m, 0.2}) printBasin(va, vb, q, T_true, params, offset);
        }
      }
      printAssociationOracle(va, vb, T_true, params);
      const PatchShares s = patchShares(r, sweeps[i], sweeps[j]);
      std::printf("verified %zu of %zu source patches on target patches (%zu source patches)\n", s.verified, s.landing,
                  s.source);
      if (r.pair.pose.success && r.pair.returns_refined) {
        slideProfile(va, vb, r.pair.pose, params);
        const SurfaceCount n = surfacesAlongWeakest(va, vb, r.pair.pose, params);
        std::printf("  surfaces along the weakest translation (%.2f, %.2f, %.2f): effective %.1f, largest share %.2f\n",
                    n.direction.x(), n.direction.y(), n.direction.z(), n.effective, n.largest_share);
        for (const double offset : {0.1, params.returns.basin_offset_m, 0.2}) printBasin(va, vb, r.pair.pose, T_true, params, offset);
        printSplitHalves(sweeps[i], vb, r.pair.pose.T_target_source, T_true, params);
        printReturnsFreeSpace(va, vb, r.pair.pose.T_target_source, "the claimed pose", params);
      }
      if (r.pair.pose.success) printTruthStart(va, vb, r.pair.pose, T_true, params);
      if (r.pair.pose.success && r.pair.edge_information.determinant() > 0.0) {  // is the claimed certainty consistent with the error? (chi-square, 6 dof)
        const gasp::eval::NeesParts edge = gasp::eval::neesParts(r.pair.pose.T_target_source, T_true, r.pair.edge_information);
        gasp::eval::NeesParts own;
        own.all = std::numeric_limits<double>::quiet_NaN();
        if (r.pair.pose.information.determinant() > 0.0)
          own = gasp::eval::neesParts(r.pair.pose.T_target_source, T_true, r.pair.pose.information);
        std::printf("NEES with the edge information %.1f (translation %.1f, rotation %.1f), with the refinement's %.1f; "
                    "95 %% of chi-square(6) below %.2f\n",
                    edge.all, edge.translation, edge.rotation, own.all, gasp::eval::kChiSquare6Quantile95);
        // The translation error against the claimed translation covariance's axes.
        const gasp::eval::Vector6 xi = gasp::eval::leftPerturbation(r.pair.pose.T_target_source, T_true);
        const Eigen::Matrix3d C = r.pair.edge_information.inverse().topLeftCorner<3, 3>();
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(C);
        for (int k = 2; k >= 0; --k)
          std::printf("  translation axis (%.2f, %.2f, %.2f): sigma %.2f cm, error along it %.2f cm\n", eig.eigenvectors()(0, k),
                      eig.eigenvectors()(1, k), eig.eigenvectors()(2, k), 100.0 * std::sqrt(std::max(0.0, eig.eigenvalues()(k))),
                      100.0 * eig.eigenvectors().col(k).dot(xi.head<3>()));
      }
      return 0;
    }
    std::printf("| Skip | Pairs | Right (5 cm, 0.5 deg) | Coarse (20 cm, 5 deg) | Wrong | No estimate (sharing >= 30 %%) | Median error of the right | Worst right | Median time [ms] | Deskewed (stage 8) |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
    for (const int k : skips) {
      int pairs = 0, right = 0, coarse = 0, wrong = 0, missed = 0, deskewed = 0;
      std::vector<double> cm, deg, ms;
      double worst_cm = 0.0, worst_deg = 0.0;
      for (std::size_t i = 0; i + static_cast<std::size_t>(k) < sweeps.size(); ++i) {
        const std::size_t j = i + static_cast<std::size_t>(k);
        const auto t0 = std::chrono::steady_clock::now();
        std::optional<gasp::Isometry3> T;
        std::optional<PatchShares> share;
        std::optional<gasp::Matrix6d> information;
        if ((shares || nees || slides) && method == "gasp") {  // the pair's patch shares, information or slides too
          const gasp::RangePairResult r = gasp::registerRangeScans(sweeps[i], sweeps[j], params);
          deskewed += r.pair.sweep_motion.moving;
          if (slides && (r.pair.returns_refined || (!r.pair.pose.success && r.pair.dense_rounds_run > 0))) {
            const gasp::Isometry3 T_true = truth[j].T_world_camera.inverse() * truth[i].T_world_camera;
            const gasp::DepthView va = gasp::makeRangeView(sweeps[i], params.segment, params.returns);
            const gasp::DepthView vb = gasp::makeRangeView(sweeps[j], params.segment, params.returns);
            if (r.pair.pose.success) {
              printSlide(i, j, "claimed", r.pair.pose.T_target_source, T_true, slideProfile(va, vb, r.pair.pose, params, false));
            } else {
              const gasp::RegistrationResult q =
                  gasp::refineOnReturns(*va.returns, *vb.returns, r.pair.pose.T_target_source, params.returns,
                                        params.refine.solver, vb.superpixels.max_incidence_deg);
              if (q.success) printSlide(i, j, "refused", q.T_target_source, T_true, slideProfile(va, vb, q, params, false));
            }
          }
          if (r.pair.pose.success) {
            T = r.pair.pose.T_target_source, information = r.pair.edge_information;
            if (shares) share = patchShares(r, sweeps[i], sweeps[j]);
          }
        } else {
          const PairOutcome o = registerPair(sweeps[i], sweeps[j], method, params);
          T = o.T_target_source;
          deskewed += o.deskewed;
        }
        ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
        ++pairs;
        const gasp::Isometry3 T_true = truth[j].T_world_camera.inverse() * truth[i].T_world_camera;
        if (!T) {
          if (const double shared = sharedDepth(sweeps[i], sweeps[j], T_true, params); shared >= 0.3) {
            ++missed;
            std::printf("no estimate: sweeps %zu -> %zu, sharing %.0f %% of their depth\n", i, j, 100.0 * shared);
          }
          continue;
        }
        const gasp::Isometry3 e = T_true.inverse() * *T;
        const double e_cm = 100.0 * e.translation().norm(), e_deg = Eigen::AngleAxisd(e.linear()).angle() * 180.0 / M_PI;
        if (share)
          std::printf("shares %zu %zu %s landing %zu/%zu verified %zu/%zu inliers %d violations %.3f/%.3f occluded %.3f\n",
                      i, j, e_cm <= 5.0 && e_deg <= 0.5 ? "right" : e_cm <= 20.0 && e_deg <= 5.0 ? "coarse" : "wrong",
                      share->landing, share->source, share->verified, share->landing, share->inliers, share->violation,
                      share->violation_lesser, share->occluded);
        if (information && information->determinant() > 0.0) {
          const gasp::eval::NeesParts x = gasp::eval::neesParts(*T, T_true, *information);
          std::printf("nees %zu %zu %s %.2f cm %.3f deg: %.2f (translation %.2f, rotation %.2f)\n", i, j,
                      e_cm <= 5.0 && e_deg <= 0.5 ? "right" : e_cm <= 20.0 && e_deg <= 5.0 ? "coarse" : "wrong", e_cm, e_deg,
                      x.all, x.translation, x.rotation);
        }
        if (e_cm <= 5.0 && e_deg <= 0.5) {
          ++right;
          cm.push_back(e_cm), deg.push_back(e_deg);
          worst_cm = std::max(worst_cm, e_cm), worst_deg = std::max(worst_deg, e_deg);
        } else if (e_cm <= 20.0 && e_deg <= 5.0) {
          ++coarse;
          std::printf("coarse pose: sweeps %zu -> %zu, %.2f cm, %.3f deg off\n", i, j, e_cm, e_deg);
        } else {
          ++wrong;
          std::printf("wrong pose: sweeps %zu -> %zu, %.2f cm, %.3f deg off\n", i, j, e_cm, e_deg);
        }
      }
      std::printf("| %d | %d | %d | %d | %d | %d (%d) | %.2f cm, %.3f deg | %.2f cm, %.3f deg | %.1f | %d |\n", k, pairs,
                  right, coarse, wrong, pairs - right - coarse - wrong, missed, median(cm), median(deg), worst_cm,
                  worst_deg, median(ms), deskewed);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
