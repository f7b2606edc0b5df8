#include "gasp/pipeline/sweep_motion.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/core/range_scan.h"
#include "gasp/core/statistics.h"
#include "gasp/pipeline/returns_stage.h"
#include "gasp/registration/refinement.h"
#include "return_term.h"

namespace gasp {

void validate(const SweepMotionParams& p) {
  auto require = [](bool ok, const char* what) {
    if (!ok) throw Error(std::string("sweep motion parameters: ") + what);
  };
  require(p.speed_sigma_mps > 0 && std::isfinite(p.speed_sigma_mps), "speed_sigma_mps must be > 0 and finite");
  require(p.rate_sigma_radps > 0 && std::isfinite(p.rate_sigma_radps), "rate_sigma_radps must be > 0 and finite");
  require(p.sectors >= 16 && p.sectors <= 4096, "sectors must be in [16, 4096]");
  require(p.false_alarm >= 1e-12 && p.false_alarm < 1, "false_alarm must be in [1e-12, 1)");
}

namespace {

using Vector18d = Eigen::Matrix<double, 18, 1>;
using Matrix18d = Eigen::Matrix<double, 18, 18>;
using Matrix12d = Eigen::Matrix<double, 12, 12>;

/// A return of the source sweep with its column's time.
struct TimedReturn {
  Eigen::Vector3d p;  ///< sensor frame at its time [m]
  double t = 0.0;     ///< after the sweep's start [s]
};

/// A term: the source return, and the target's plane in the target's sensor frame at its time.
struct MotionTerm {
  TimedReturn source;
  Eigen::Vector3d q, n;
  double t_target = 0.0;
};

/// The unknowns: T_target_source between the start poses, and each sweep's twist.
struct MotionState {
  Isometry3 T = Isometry3::Identity();
  CameraTwist source, target;
};

/// The sensor's pose at t relative to its start, for a sweep moving at `twist`.
Isometry3 at(const CameraTwist& twist, double t) { return twistMotion(twist, t); }

/// Terms of one round: each source return carried to its sweep's start and into the target's
/// start frame, then into the target's sensor frame at the time of the column it falls in (found
/// by looking up twice: the column depends on where the sensor was).
std::vector<MotionTerm> motionTerms(const std::vector<TimedReturn>& points, const SweepReturns& target,
                                    const MotionState& s, double gate, int look_up_columns, double min_cos) {
  const RangeScan& scan = target.scan();
  const auto termsOf = [&](std::size_t begin, std::size_t end, std::vector<MotionTerm>& terms) {
    Eigen::Vector3d x, n;
    for (std::size_t k = begin; k < end; ++k) {
      const TimedReturn& r = points[k];
      const Eigen::Vector3d p0 = s.T * (at(s.source, r.t) * r.p);  // target's start frame
      double t = 0.0;
      int i = -1;
      for (int pass = 0; pass < 3; ++pass) {
        const int j = target.lookUp(at(s.target, t).inverse() * p0, look_up_columns);
        if (j < 0) break;
        const double tj = columnTime(scan, j % target.cols());
        const bool settled = j == i || tj == t;
        i = j, t = tj;
        if (settled) break;
      }
      if (i < 0) continue;
      const Eigen::Vector3d pt = at(s.target, t).inverse() * p0;
      if (returnTerm(pt, target, gate, look_up_columns, min_cos, x, n) < 0) continue;
      terms.push_back(MotionTerm{r, x, n, t});
    }
  };
  constexpr std::size_t kPointsPerTask = 2048;
  const std::size_t blocks = (points.size() + kPointsPerTask - 1) / kPointsPerTask;
  std::vector<std::vector<MotionTerm>> per_block(blocks);
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
    termsOf(b * kPointsPerTask, std::min(points.size(), (b + 1) * kPointsPerTask), per_block[b]);
  });
  std::vector<MotionTerm> terms;
  for (auto& block : per_block) terms.insert(terms.end(), block.begin(), block.end());
  return terms;
}

/// The residual n.(x - q) in the target's start frame and its gradient over the unknowns' steps
/// [d_t d_r (left perturbation of T, as RegistrationResult::information), dv_s dw_s, dv_t dw_t]
/// (the twists' rotations to first order in their time).
double residual(const MotionTerm& m, const MotionState& s, Vector18d& J) {
  const Isometry3 Ms = at(s.source, m.source.t), Mt = at(s.target, m.t_target);
  const Eigen::Vector3d ps_rot = Ms.linear() * m.source.p;  // the source return's rotated part
  const Eigen::Vector3d x = s.T * (Ms * m.source.p);
  const Eigen::Vector3d qt_rot = Mt.linear() * m.q;
  const Eigen::Vector3d q = Mt * m.q, n = Mt.linear() * m.n;
  const double r = n.dot(x - q);
  const Eigen::Vector3d n_in_source = s.T.linear().transpose() * n;
  const double ts = m.source.t, tt = m.t_target;
  J.segment<3>(0) = n;
  J.segment<3>(3) = x.cross(n);
  J.segment<3>(6) = ts * n_in_source;
  J.segment<3>(9) = ts * ps_rot.cross(n_in_source);
  J.segment<3>(12) = -tt * n;
  J.segment<3>(15) = -tt * qt_rot.cross(n) + tt * n.cross(x - q);
  return r;
}

void apply(const Vector18d& d, MotionState& s) {
  Isometry3 step = Isometry3::Identity();
  const double angle = d.segment<3>(3).norm();
  if (angle > 0.0) step.linear() = Eigen::AngleAxisd(angle, d.segment<3>(3) / angle).toRotationMatrix();
  step.translation() = d.segment<3>(0);
  s.T = step * s.T;
  s.source.v_mps += d.segment<3>(6), s.source.w_radps += d.segment<3>(9);
  s.target.v_mps += d.segment<3>(12), s.target.w_radps += d.segment<3>(15);
}

Vector18d twists(const MotionState& s) {
  Vector18d x = Vector18d::Zero();
  x.segment<3>(6) = s.source.v_mps, x.segment<3>(9) = s.source.w_radps;
  x.segment<3>(12) = s.target.v_mps, x.segment<3>(15) = s.target.w_radps;
  return x;
}

/// The normal equations of one set of terms at `s`: information H (with the twists' prior),
/// gradient g, and the terms' RMS residual.
struct NormalEquations {
  Matrix18d H = Matrix18d::Zero();
  Vector18d g = Vector18d::Zero();
  double rms_m = 0.0;
};

NormalEquations normalEquations(const std::vector<MotionTerm>& terms, const MotionState& s,
                                const RefinementParams& solver, const Vector18d& prior) {
  NormalEquations e;
  const double info_scale = 1.0 / (solver.noise_sigma_m * solver.noise_sigma_m);
  Vector18d J;
  double r2 = 0.0;
  for (const MotionTerm& m : terms) {
    const double r = residual(m, s, J);
    const double w = robustWeight(solver, r) * info_scale;
    e.H.selfadjointView<Eigen::Lower>().rankUpdate(J, w);
    e.g += w * r * J;
    r2 += r * r;
  }
  e.H = e.H.selfadjointView<Eigen::Lower>();
  e.H.diagonal() += prior;
  e.g += prior.cwiseProduct(twists(s));
  e.rms_m = terms.empty() ? 0.0 : std::sqrt(r2 / static_cast<double>(terms.size()));
  return e;
}

/// Hotelling's test of the twists' efficient score at rest, with the source sweep cut into
/// `sectors` by firing time: each sector's score (its gradient of the twists less what the pose
/// absorbs) is one sample, so residuals correlated along a surface count once. Returns the F
/// statistic (12, K - 12 degrees of freedom at rest; negative when it cannot be formed) and K,
/// the sectors with terms.
std::pair<double, int> sectorScoreTest(const std::vector<MotionTerm>& terms, const MotionState& s,
                                       const RefinementParams& solver, const NormalEquations& e, double duration_s,
                                       int sectors) {
  std::vector<Vector18d> g(static_cast<std::size_t>(sectors), Vector18d::Zero());
  std::vector<int> count(static_cast<std::size_t>(sectors), 0);
  Vector18d J;
  for (const MotionTerm& m : terms) {
    const double r = residual(m, s, J);
    const int k = std::clamp(static_cast<int>(m.source.t / duration_s * sectors), 0, sectors - 1);
    g[static_cast<std::size_t>(k)] += robustWeight(solver, r) * r * J;
    ++count[static_cast<std::size_t>(k)];
  }
  const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> pose(e.H.topLeftCorner<6, 6>());
  if (pose.info() != Eigen::Success || !pose.isPositive()) return {-1.0, 0};
  const Eigen::Matrix<double, 12, 6> absorbed = e.H.bottomLeftCorner<12, 6>() * pose.solve(Eigen::Matrix<double, 6, 6>::Identity());
  std::vector<Eigen::Matrix<double, 12, 1>> u;
  for (int k = 0; k < sectors; ++k)
    if (count[static_cast<std::size_t>(k)] > 0)
      u.push_back(g[static_cast<std::size_t>(k)].tail<12>() - absorbed * g[static_cast<std::size_t>(k)].head<6>());
  const int K = static_cast<int>(u.size());
  if (K <= 12) return {-1.0, K};
  Eigen::Matrix<double, 12, 1> mean = Eigen::Matrix<double, 12, 1>::Zero();
  for (const auto& x : u) mean += x;
  mean /= K;
  Eigen::Matrix<double, 12, 12> S = Eigen::Matrix<double, 12, 12>::Zero();
  for (const auto& x : u) S += (x - mean) * (x - mean).transpose();
  S /= (K - 1);
  const Eigen::LDLT<Eigen::Matrix<double, 12, 12>> ldlt(S);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) return {-1.0, K};
  const double t2 = K * mean.dot(ldlt.solve(mean));
  return {t2 * (K - 12) / (12.0 * (K - 1)), K};
}

/// The claimed pose's largest standard deviations with both twists unknown: the pose block of
/// the inverse information (the Schur complement of the twists, their prior included), its
/// translation [m] and its rotation [rad] times the RMS range of the terms' target points.
struct FreeMotion {
  double sigma_m = 0.0, rotation_m = 0.0;
};

FreeMotion freeMotion(const std::vector<MotionTerm>& terms, const NormalEquations& e) {
  const Eigen::LDLT<Matrix12d> twists(e.H.bottomRightCorner<12, 12>());
  const Eigen::Matrix<double, 6, 12> H_pt = e.H.topRightCorner<6, 12>();
  const Eigen::Matrix<double, 6, 6> schur = e.H.topLeftCorner<6, 6>() - H_pt * twists.solve(H_pt.transpose());
  const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> pose(schur);
  FreeMotion out;
  if (twists.info() != Eigen::Success || !twists.isPositive() || pose.info() != Eigen::Success || !pose.isPositive()) {
    out.sigma_m = out.rotation_m = std::numeric_limits<double>::infinity();
    return out;
  }
  const Eigen::Matrix<double, 6, 6> cov = pose.solve(Eigen::Matrix<double, 6, 6>::Identity());
  const auto largest = [](const Eigen::Matrix3d& c) {
    return std::sqrt(std::max(0.0, Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(c).eigenvalues().maxCoeff()));
  };
  double r2 = 0.0;
  for (const MotionTerm& m : terms) r2 += m.q.squaredNorm();
  const double rms_range = terms.empty() ? 0.0 : std::sqrt(r2 / static_cast<double>(terms.size()));
  out.sigma_m = largest(cov.topLeftCorner<3, 3>());
  out.rotation_m = largest(cov.bottomRightCorner<3, 3>()) * rms_range;
  return out;
}

}  // namespace

SweepMotion estimateSweepMotion(const SweepReturns& source, const SweepReturns& target, const Isometry3& T_target_source,
                                const ReturnsRefineParams& p, const RefinementParams& solver,
                                const SweepMotionParams& params, double max_incidence_deg) {
  validate(params);
  validate(p);
  validate(solver);
  if (!(max_incidence_deg > 0.0 && max_incidence_deg < 90.0))
    throw Error("sweep motion: max_incidence_deg must be in (0, 90)");
  const auto t0 = std::chrono::steady_clock::now();
  SweepMotion out;
  out.T_target_source = T_target_source;
  const auto done = [&](std::string reason) {
    out.reason = std::move(reason);
    out.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return out;
  };
  if (!sweepTimed(source.scan()) || !sweepTimed(target.scan()))
    return done("sweep motion: a sweep's columns carry no firing times (no sweep duration, or a point cloud)");
  std::vector<TimedReturn> points;
  long valid = 0;
  for (int r = 0; r < source.rows(); ++r)
    for (int c = 0; c < source.cols(); c += p.column_step)
      if (const Eigen::Vector3d& q = source.point(r, c); q.allFinite() && valid++ % p.return_step == 0)
        points.push_back({q, columnTime(source.scan(), c)});
  const double min_cos = std::cos(max_incidence_deg * M_PI / 180.0);
  Vector18d prior = Vector18d::Zero();  // the twists' prior information (diagonal)
  for (int k : {6, 12}) {
    prior.segment<3>(k).setConstant(1.0 / (params.speed_sigma_mps * params.speed_sigma_mps));
    prior.segment<3>(k + 3).setConstant(1.0 / (params.rate_sigma_radps * params.rate_sigma_radps));
  }
  MotionState s;
  s.T = T_target_source;
  const auto tooFew = [&](std::size_t n, const char* when) {
    return done("sweep motion: " + std::to_string(n) + " point-to-plane terms " + when + " (at least 18 needed)");
  };
  {  // The score test at rest, at the claimed pose and the tightest gate: still sweeps end here.
    const std::vector<MotionTerm> terms = motionTerms(points, target, s, p.gates_m.back(), p.look_up_columns, min_cos);
    if (terms.size() < 18) return tooFew(terms.size(), "at rest");
    const NormalEquations e = normalEquations(terms, s, solver, prior);
    const auto [f, sectors] =
        sectorScoreTest(terms, s, solver, e, source.scan().sweep_duration_s, params.sectors);
    out.terms = static_cast<int>(terms.size());
    out.rms_residual_m = e.rms_m;
    out.sectors = sectors;
    if (f < 0.0)
      return done("sweep motion: no score test (" + std::to_string(sectors) + " sectors with terms, at least 13 needed)");
    out.score_f = f;
    out.score_bound = fisherQuantile(1.0 - params.false_alarm, 12.0, sectors - 12.0);
    if (f <= out.score_bound) {
      const FreeMotion unknown = freeMotion(terms, e);
      out.free_motion_sigma_m = unknown.sigma_m;
      out.free_motion_rotation_m = unknown.rotation_m;
      const double gate = p.gates_m.back();  // beyond it a return is not on the surface
      out.determined = unknown.sigma_m <= gate && unknown.rotation_m <= gate;
      char buf[300];
      std::snprintf(buf, sizeof buf,
                    "sweep motion: at rest (score F %.2f over %d sectors, at most %.2f); with the motions unknown "
                    "the pose's sigma is %.2f cm, its rotation's %.2f cm at the terms' range (%s the returns' last "
                    "gate, %.2f cm)",
                    f, sectors, out.score_bound, 100.0 * unknown.sigma_m, 100.0 * unknown.rotation_m,
                    out.determined ? "within" : "beyond", 100.0 * gate);
      return done(buf);
    }
  }
  NormalEquations e;
  constexpr int kStepsPerRound = 3;  // Gauss-Newton steps on one round's terms
  for (int round = 0; round < p.max_rounds; ++round) {
    const double gate = p.gates_m[std::min(static_cast<std::size_t>(round), p.gates_m.size() - 1)];
    const std::vector<MotionTerm> terms = motionTerms(points, target, s, gate, p.look_up_columns, min_cos);
    if (terms.size() < 18) return tooFew(terms.size(), ("in round " + std::to_string(round + 1)).c_str());
    const MotionState before = s;
    for (int step = 0; step < kStepsPerRound; ++step) {
      e = normalEquations(terms, s, solver, prior);
      const Eigen::LDLT<Matrix18d> ldlt(e.H);
      if (ldlt.info() != Eigen::Success || !ldlt.isPositive())
        return done("sweep motion: the solve's information is not positive definite");
      const Vector18d d = -ldlt.solve(e.g);
      if (!d.allFinite()) return done("sweep motion: the solve diverged");
      apply(d, s);
      out.terms = static_cast<int>(terms.size());
      out.rms_residual_m = e.rms_m;
      if (d.segment<6>(0).norm() < 1e-7 && d.tail<12>().norm() < 1e-6) break;
    }
    double moved2 = 0.0;
    for (const TimedReturn& q : points)
      moved2 += (s.T * (at(s.source, q.t) * q.p) - before.T * (at(before.source, q.t) * q.p)).squaredNorm();
    const bool last_gate = round + 1 >= static_cast<int>(p.gates_m.size());
    if (last_gate && std::sqrt(moved2 / static_cast<double>(points.size())) < p.converged_m) break;
  }
  out.estimated = out.moving = true;
  out.T_target_source = s.T;
  out.source_twist = s.source;
  out.target_twist = s.target;
  return done("");
}

}  // namespace gasp
