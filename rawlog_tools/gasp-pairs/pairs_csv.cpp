#include "pairs_csv.h"

#include <Eigen/Geometry>

#include <cmath>
#include <sstream>

namespace gasp::pairs {

namespace {

/// Translation [m] and rotation [deg] of A^-1 B, or two empty fields.
std::string difference(const std::optional<Isometry3>& A, const std::optional<Isometry3>& B) {
  if (!A || !B) return std::string(",");
  const Isometry3 E = A->inverse() * *B;
  return std::to_string(translationNorm(E)) + ',' + std::to_string(rotationAngle(E) * 180.0 / M_PI);
}

}  // namespace

std::string pairsCsvHeader() {
  return "skip,method,from,to,estimated,t_err_m,r_err_deg,ms,associations,inliers,violation_ratio,occluded_ratio,"
         "consistent,occluded,violations,one_way,guided_support,finer_scale,slide_moved,dense_terms,dense_rounds,"
         "dense_last_step_m,dense_shortened,dense_stopped,"
         "precision,verified,verified_precision,verified_density,agreement,agreement_truth,tx,ty,tz,qx,qy,qz,qw,"
         "motion_t_m,motion_r_deg,ref_icp_t_m,ref_icp_r_deg,est_vs_ref_icp_t_m,est_vs_ref_icp_r_deg,"
         "est_icp_t_m,est_icp_r_deg,icp_est_vs_ref_icp_t_m,icp_est_vs_ref_icp_r_deg,verified_precision_ref_icp,"
         "rgb_inliers,rgb_parallax_px,rgb_r_vs_ref_deg,rgb_r_vs_est_deg,rgb_r_vs_ref_icp_deg,nees,nees_t,nees_r,"
         "nees_refinement,violation_ratio_lesser,violation_blob_share_lesser,violation_blob_share,partial,free_directions,"
         "observed_t_err_m,observed_r_err_deg,uniqueness_log_ratio,alternative_taken,reason";
}

std::string pairsCsvRow(const eval::PairOutcome& o, const std::string& method, const MethodRun& run,
                        const PairsCsvChecks& checks) {
  std::ostringstream s;
  s << o.skip << ',' << method << ',' << o.from << ',' << o.to << ',' << (o.estimated ? 1 : 0) << ',';
  if (o.estimated) s << o.t_err_m << ',' << o.r_err_deg;  // no error without an estimate
  else s << ',';
  s << ',' << o.ms << ',' << run.associations << ',' << run.inliers << ',' << run.violation_ratio << ','
    << run.occluded_ratio << ',' << run.consistent << ',' << run.occluded << ',' << run.violations << ','
    << run.one_way << ',' << run.guided_support << ',' << (run.finer_scale ? 1 : 0) << ','
    << (run.slide_moved ? 1 : 0) << ',' << run.dense_terms << ',' << run.dense_rounds << ','
    << run.dense_last_step_m << ',' << run.dense_shortened << ',' << (run.dense_stopped ? 1 : 0) << ',';
  if (run.free_quality) s << run.free_quality->precision();
  s << ',';
  if (const auto& vq = run.verified_quality) s << vq->associations << ',' << vq->precision() << ',' << vq->density();
  else s << ",,";
  s << ',';
  if (run.agreement_estimate) s << *run.agreement_estimate;
  s << ',';
  if (run.agreement_truth) s << *run.agreement_truth;
  std::optional<Isometry3> T_est;
  if (run.estimated) {
    T_est = run.T_target_source;
    const Eigen::Quaterniond q(run.T_target_source.linear());
    const auto& t = run.T_target_source.translation();
    s << ',' << t.x() << ',' << t.y() << ',' << t.z() << ',' << q.x() << ',' << q.y() << ',' << q.z() << ',' << q.w();
  } else {
    s << ",,,,,,,";
  }
  // The true motion of the pair (how far apart the views are).
  s << ',' << translationNorm(checks.T_gt) << ',' << rotationAngle(checks.T_gt) * 180.0 / M_PI;
  s << ',' << difference(checks.T_gt, checks.T_ref_icp) << ',' << difference(T_est, checks.T_ref_icp) << ','
    << difference(T_est, checks.T_est_icp) << ',' << difference(checks.T_est_icp, checks.T_ref_icp) << ',';
  if (run.verified_quality_polished) s << run.verified_quality_polished->precision();
  s << ',';
  const RgbCheck& rgb = checks.rgb;
  if (rgb.ran) s << rgb.inliers << ',' << rgb.parallax_px;
  else s << ',';
  s << ',' << rgbAngleText(rgb, rgb.T_ref) << ',' << rgbAngleText(rgb, toRgbStamps(rgb, T_est)) << ','
    << rgbAngleText(rgb, toRgbStamps(rgb, checks.T_ref_icp)) << ',';
  if (run.nees) s << run.nees->all << ',' << run.nees->translation << ',' << run.nees->rotation;
  else s << ",,";
  s << ',';
  if (run.nees_refinement) s << *run.nees_refinement;
  s << ',' << run.violation_ratio_lesser << ',' << run.violation_blob_share_lesser << ',' << run.violation_blob_share
    << ',' << (run.partial ? 1 : 0) << ',' << run.free_directions << ',';
  if (run.observed) s << run.observed->translation_m << ',' << run.observed->rotation_deg;
  else s << ',';
  s << ',';
  if (std::isfinite(run.uniqueness_log_ratio)) s << run.uniqueness_log_ratio;
  s << ',' << (run.alternative_taken ? 1 : 0) << ",\"";
  for (const char ch : o.reason) s << (ch == '"' ? "\"\"" : std::string(1, ch));  // RFC 4180 quoting
  s << '"';
  return s.str();
}

}  // namespace gasp::pairs
