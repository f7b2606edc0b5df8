#include "gasp/pipeline/pose_likelihood.h"

#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "gasp/core/depth_image.h"
#include "gasp/core/error.h"
#include "gasp/pipeline/range_view.h"
#include "gasp/pipeline/returns_stage.h"

namespace gasp {

namespace {

/// A sample's l for a residual [m] of noise sigma [m] (the header's), less violation_nats for a violation.
class InlierTerm {
 public:
  explicit InlierTerm(const PoseLikelihoodParams& p)
      : scale_(p.inlier_prior / (1.0 - p.inlier_prior) * p.outlier_range_m / std::sqrt(2.0 * M_PI)),
        violation_nats_(p.violation_nats) {}
  double operator()(double residual_m, double sigma_m, bool violation) const {
    const double e = residual_m / sigma_m;
    const double l = std::log1p(scale_ / sigma_m * std::exp(-0.5 * e * e));
    // In space the other sensor saw as empty: only a random reading explains it.
    return violation ? l - violation_nats_ : l;
  }

 private:
  double scale_, violation_nats_;
};

/// One sample's l under T_to_from (the header's), or nullopt where it lands on no measured depth.
class SampleTerm {
 public:
  SampleTerm(const DepthView& to, const PoseLikelihoodParams& p)
      : to_(to), p_(p), term_(p), gate_(to, p.free_space) {}
  std::optional<double> operator()(const Eigen::Vector3d& point, const Isometry3& T_to_from) const {
    const Eigen::Vector3d q = T_to_from * point;
    double uf = 0, vf = 0;
    if (!to_.projection.project(q, uf, vf)) return std::nullopt;
    const int ut = static_cast<int>(std::lround(uf)), vt = static_cast<int>(std::lround(vf));
    if (ut < 0 || vt < 0 || ut >= to_.depth_m.cols || vt >= to_.depth_m.rows) return std::nullopt;
    const float zt = to_.depth_m.at<float>(vt, ut);
    if (!isValidDepth(zt)) return std::nullopt;
    const double sigma = p_.sigma_m + p_.sigma_per_m2 * zt * zt;
    const double zq = to_.projection.depth(q);
    return term_(zq - zt, sigma, p_.violation_nats > 0.0 && zq < zt - gate_(ut, vt, q, zt));
  }

 private:
  const DepthView& to_;
  const PoseLikelihoodParams& p_;
  InlierTerm term_;
  FreeSpaceGate gate_;
};

/// Adds the patches' means of l(a) - l(b) over their counted samples (sum, count per patch),
/// outside the dead band.
void addPatchMeans(const std::vector<double>& sum, const std::vector<int>& count, const PoseLikelihoodParams& p,
                   LikelihoodRatio& out) {
  for (std::size_t k = 0; k < sum.size(); ++k) {
    if (count[k] == 0) continue;
    ++out.patches;
    const double mean = sum[k] / count[k];
    if (std::abs(mean) <= p.patch_deadband_nats) continue;
    out.log_ratio += mean;
    out.standard_error += mean * mean;  // the square root is taken at the end
  }
}

/// Calls visit(k, label, point) for every sample of `from` (every pixel_step-th pixel with valid
/// depth on a patch), k its index in the grid of sampled pixels; false when `from` has none.
template <typename Visit>
bool forEachSample(const DepthView& from, const DepthView& to, const PoseLikelihoodParams& p, const Visit& visit) {
  const cv::Mat& d = from.depth_m;
  const cv::Mat& labels = from.segmentation.labels;
  const std::size_t n = from.segmentation.patches.size();
  if (n == 0 || labels.size() != d.size() || to.depth_m.empty()) return false;
  std::size_t k = 0;
  for (int v = 0; v < d.rows; v += p.pixel_step)
    for (int u = 0; u < d.cols; u += p.pixel_step, ++k) {
      const int label = labels.at<int>(v, u);
      const float z0 = d.at<float>(v, u);
      if (label < 0 || static_cast<std::size_t>(label) >= n || !isValidDepth(z0)) continue;
      visit(k, static_cast<std::size_t>(label), from.projection.unproject(u, v, z0));
    }
  return true;
}

/// `from`'s samples' l under T_to_from (NaN where one lands on no measured depth), by grid index.
std::vector<double> samplesOneWay(const DepthView& from, const DepthView& to, const Isometry3& T_to_from,
                                  const PoseLikelihoodParams& p) {
  std::vector<double> l;
  const SampleTerm term(to, p);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  forEachSample(from, to, p, [&](std::size_t k, std::size_t, const Eigen::Vector3d& point) {
    if (l.size() <= k) l.resize(k + 1, nan);
    l[k] = term(point, T_to_from).value_or(nan);
  });
  return l;
}

/// Adds `from`'s patches' means of l(a) - l(b) over their counted samples, outside the dead band;
/// l(a) from `cached_a` (samplesOneWay under T_to_from_a) when given.
void oneWay(const DepthView& from, const DepthView& to, const Isometry3& T_to_from_a, const Isometry3& T_to_from_b,
            const PoseLikelihoodParams& p, const std::vector<double>* cached_a, LikelihoodRatio& out) {
  const std::size_t n = from.segmentation.patches.size();
  std::vector<double> sum(n, 0.0);
  std::vector<int> count(n, 0);
  const SampleTerm term(to, p);
  const bool sampled = forEachSample(from, to, p, [&](std::size_t k, std::size_t label, const Eigen::Vector3d& point) {
    double la = 0.0;
    if (cached_a) {
      if (k >= cached_a->size() || std::isnan((*cached_a)[k])) return;
      la = (*cached_a)[k];
    } else if (const auto a = term(point, T_to_from_a)) {
      la = *a;
    } else {
      return;
    }
    const auto lb = term(point, T_to_from_b);
    if (!lb) return;
    sum[label] += la - *lb;
    ++count[label];
  });
  if (sampled) addPatchMeans(sum, count, p, out);
}

/// oneWay() on the sweeps' returns (returnsLogLikelihoodRatio).
void oneWayOnReturns(const DepthView& from, const DepthView& to, const Isometry3& T_to_from_a,
                     const Isometry3& T_to_from_b, const PoseLikelihoodParams& p, double range_sigma_m,
                     double max_incidence_deg, LikelihoodRatio& out) {
  const SweepReturns& returns = *from.returns;
  const cv::Mat& labels = from.segmentation.labels;
  const std::size_t n = from.segmentation.patches.size();
  if (n == 0 || labels.rows != returns.rows()) return;
  const int b = rangeBinColumns(returns.scan());  // the binned cell of a return: same row, column / b
  std::vector<double> sum(n, 0.0);
  std::vector<int> count(n, 0);
  const InlierTerm term(p);
  const auto l = [&](const Eigen::Vector3d& point, const Isometry3& T) -> std::optional<double> {
    const ReturnLanding landing = landOnReturns(*to.returns, T * point, range_sigma_m, max_incidence_deg);
    if (landing.index < 0) return std::nullopt;
    return term(landing.plane_m, range_sigma_m, landing.beyond_m < -landing.gate_m);
  };
  for (int r = 0; r < returns.rows(); ++r)
    for (int c = 0; c < returns.cols(); ++c) {
      const Eigen::Vector3d& point = returns.point(r, c);
      if (!point.allFinite() || c / b >= labels.cols) continue;
      const int label = labels.at<int>(r, c / b);
      if (label < 0 || static_cast<std::size_t>(label) >= n) continue;
      const auto la = l(point, T_to_from_a), lb = l(point, T_to_from_b);
      if (!la || !lb) continue;
      const std::size_t k = static_cast<std::size_t>(label);
      sum[k] += *la - *lb;
      ++count[k];
    }
  addPatchMeans(sum, count, p, out);
}

}  // namespace

LikelihoodRatio logLikelihoodRatio(const DepthView& source, const DepthView& target, const Isometry3& T_a,
                                   const Isometry3& T_b, const PoseLikelihoodParams& params) {
  LikelihoodRatio out;
  if (!T_a.matrix().allFinite() || !T_b.matrix().allFinite()) return out;
  oneWay(source, target, T_a, T_b, params, nullptr, out);
  oneWay(target, source, T_a.inverse(), T_b.inverse(), params, nullptr, out);
  out.standard_error = std::sqrt(out.standard_error);
  return out;
}

PoseSamples poseSamples(const DepthView& source, const DepthView& target, const Isometry3& T_a,
                        const PoseLikelihoodParams& params) {
  PoseSamples a;
  a.T_target_source = T_a;
  a.pixel_step = params.pixel_step;
  if (!T_a.matrix().allFinite()) return a;
  a.source_to_target = samplesOneWay(source, target, T_a, params);
  a.target_to_source = samplesOneWay(target, source, T_a.inverse(), params);
  return a;
}

LikelihoodRatio logLikelihoodRatio(const DepthView& source, const DepthView& target, const PoseSamples& a,
                                   const Isometry3& T_b, const PoseLikelihoodParams& params) {
  if (a.pixel_step != params.pixel_step)
    throw Error("logLikelihoodRatio: the kept samples were taken every " + std::to_string(a.pixel_step) +
                " pixels, the ratio asks for every " + std::to_string(params.pixel_step));
  LikelihoodRatio out;
  const Isometry3& T_a = a.T_target_source;
  if (!T_a.matrix().allFinite() || !T_b.matrix().allFinite()) return out;
  oneWay(source, target, T_a, T_b, params, &a.source_to_target, out);
  oneWay(target, source, T_a.inverse(), T_b.inverse(), params, &a.target_to_source, out);
  out.standard_error = std::sqrt(out.standard_error);
  return out;
}

LikelihoodRatio returnsLogLikelihoodRatio(const DepthView& source, const DepthView& target, const Isometry3& T_a,
                                          const Isometry3& T_b, const PoseLikelihoodParams& params,
                                          double range_sigma_m, double max_incidence_deg) {
  LikelihoodRatio out;
  if (!T_a.matrix().allFinite() || !T_b.matrix().allFinite() || !source.returns || !target.returns) return out;
  oneWayOnReturns(source, target, T_a, T_b, params, range_sigma_m, max_incidence_deg, out);
  oneWayOnReturns(target, source, T_a.inverse(), T_b.inverse(), params, range_sigma_m, max_incidence_deg, out);
  out.standard_error = std::sqrt(out.standard_error);
  return out;
}

}  // namespace gasp
