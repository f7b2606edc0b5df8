// gasp-loops: loop detection without appearance and without odometry, scored against a reference.
//   gasp-loops --tum DIR | --rawlog FILE --gt GT.txt [--every 10] [--first N] [--max-frames N]
//              [--candidates 3] [--min-gap 5] [--gt-offset 0] [--drift M,DEG]
//              [--csv DETECTIONS.csv] [--curve-csv PR.csv] [--params FILE]
// Every --every-th frame is a keyframe (no odometry chooses them or predicts anything). Each
// keyframe queries the place descriptors of the keyframes at least --min-gap keyframes before it
// (gasp/association/place_descriptor.h), takes the --candidates nearest and registers itself to
// each with the whole pair front-end and no initial guess, as gasp-slam's relocalisation does
// (registerLoopClosure); its detection is the successful registration with the most inliers,
// scored by its inliers. By the reference: a keyframe is a positive when a keyframe at least
// --min-gap before it shares at least 30 % of its depth at the reference pose (depthAgreement,
// docs/evaluation.md "Failures"); a detection is correct when its pose is within 5 cm and 2 deg
// of the reference (the pair protocol's bound), and consistent when its error is within its own
// information (xi^T Lambda xi <= loop_closure.gate_chi2: what a pose graph takes it for). Prints
// the positives, the detections, the precision and recall at the loop closer's own threshold
// (loop_closure.relocalisation_min_inliers) and the recall at 100 % precision, by either rule.
// With --drift M,DEG, whether those detections close an injected drift: the odometry
// (DepthOdometry over every frame between the first and the last keyframe) composed between
// consecutive keyframes makes a chain; every step
// is then bent by the same small motion (a turn about the camera's vertical and a shift along its
// x) so that the chain ends about M metres and DEG degrees off; the chain and every registration
// at or above the loop closer's threshold are optimised as a pose graph (pose_graph_optimizer.h;
// a closure the optimised graph contradicts is dropped, as gasp-slam does), starting from the
// bent chain. Prints the keyframes' ATE of the chain and of the optimised graph, with and without
// the drift.
// Exit codes: 0 success, 1 bad input, 2 usage error, 3 written, but --drift found no odometry chain
// (the odometry lost track between two keyframes).
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "gasp/association/place_descriptor.h"
#include "gasp/core/error.h"
#include "gasp/core/format.h"
#include "gasp/core/pose_perturbation.h"
#include "gasp/core/tum_trajectory.h"
#include "gasp/eval/pair_protocol.h"
#include "gasp/eval/precision_recall.h"
#include "gasp/pipeline/depth_view.h"
#include "gasp/pipeline/visibility_check.h"
#include "gasp/rawlog/depth_sequence.h"
#include "gasp/slam/loop_closure.h"
#include "gasp/slam/loop_search.h"
#include "gasp/slam/pose_graph.h"
#include "gasp/slam/pose_graph_optimizer.h"
#include "gasp/eval/ate.h"
#include "gasp/odometry/odometry.h"
#include "cli.h"
#include "params_options.h"
#include "run_outputs.h"
#include "sequence_options.h"

namespace {

/// The share of a keyframe's depth another must show, at the reference pose, for a loop to exist.
constexpr double kPositiveShare = 0.30;

struct Keyframe {
  std::size_t frame = 0;  ///< index among the input's frames
  double timestamp = 0.0;
  std::optional<gasp::Isometry3> T_world_camera;  ///< the reference
  gasp::DepthView view;
};

/// One registration of a query keyframe to a candidate.
struct Attempt {
  std::size_t query = 0, candidate = 0;  ///< keyframe positions
  std::size_t rank = 0;                  ///< by descriptor distance, from 0
  double distance = 0.0;
  gasp::LoopClosureAttempt attempt;
  gasp::PoseConstraint constraint;
  double t_err_m = std::nan(""), r_err_deg = std::nan("");
  double chi2 = std::nan("");  ///< the error weighed by the constraint's information
  bool correct = false;        ///< within 5 cm and 2 deg
  bool consistent = false;     ///< chi2 <= gate_chi2
  double share_truth = std::nan("");  ///< the query's depth the candidate shows at the reference pose
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"gasp-loops: loop detection by place retrieval and registration, without appearance and without "
               "odometry, scored against the reference: precision and recall"};
  gasp::DepthSequenceOptions input;
  input.every = 10;
  std::string gt_path, csv_path, curve_path;
  std::size_t candidates = 3, min_gap = 5;
  double gt_offset_s = 0.0;
  std::vector<double> drift;
  gasp::tools::ParamsOptions params_options;
  gasp::SlamParams params;
  if (!params_options.preload(argc, argv, params)) return 1;
  gasp::tools::addSequenceOptions(app, input, gt_path);
  app.add_option("--candidates", candidates, "registrations per keyframe: its nearest place descriptors")
      ->capture_default_str()
      ->check(gasp::tools::atLeast(1));
  app.add_option("--min-gap", min_gap, "candidates and loops at least this many keyframes back")
      ->capture_default_str()
      ->check(gasp::tools::atLeast(1));
  app.add_option("--gt-offset", gt_offset_s,
                 "the reference looked up at the frame's time plus this [s] (TUM fr1: -0.03, docs/evaluation.md)")
      ->capture_default_str()
      ->check(gasp::tools::within(-1, 1));
  app.add_option("--drift", drift,
                 "M,DEG: bend the keyframes' odometry chain so that it ends about M metres and DEG degrees off, then "
                 "close it with the detections (a pose graph) and print the ATE")
      ->delimiter(',')
      ->expected(2);
  app.add_option("--csv", csv_path,
                 "one line per registration: query and candidate frames, rank, descriptor distance, inliers, "
                 "reason, error against the reference, correct, the share of depth the pair shows");
  app.add_option("--curve-csv", curve_path, "the precision-recall curve: threshold, true and false positives, precision, recall");
  params_options.add(app);
  if (const int code = gasp::tools::parseCommandLine(app, argc, argv); code >= 0) return code;
  if (const int code = params_options.printIfAsked(params); code >= 0) return code;
  if (input.tum_dir.empty() && input.rawlog_path.empty()) {
    std::cerr << "error: give --tum DIR or --rawlog FILE with --gt GT.txt\n";
    return 2;
  }
  if (!drift.empty() && !(std::isfinite(drift[0]) && std::isfinite(drift[1]) && drift[0] >= 0 && drift[1] >= 0 && drift[1] < 180)) {
    std::cerr << "error: --drift: expected M,DEG with M >= 0 metres and 0 <= DEG < 180 degrees\n";
    return 2;
  }

  try {
    gasp::validate(params);
    gasp::tools::RunOutputs outputs({{"--csv", csv_path}, {"--curve-csv", curve_path}},
                                    gasp::tools::sequenceInputs(input, gt_path));
    gasp::DepthSequence sequence(input);
    const gasp::Trajectory gt = gt_path.empty() ? sequence.groundTruth() : gasp::readTumTrajectory(gt_path);
    if (gt.empty()) throw gasp::Error(sequence.describe() + ": no reference (a TUM folder's groundtruth.txt, or --gt)");
    const gasp::PairParams& pair = params.odometry.pair;

    // Keyframes: segmented, described, with their reference poses.
    std::vector<Keyframe> keyframes;
    gasp::PlaceIndex places;
    while (auto frame = sequence.next()) {
      Keyframe k;
      k.frame = sequence.inputIndex();
      k.timestamp = frame->timestamp;
      if (const auto i = gasp::findNearest(gt, frame->timestamp + gt_offset_s, 0.02)) k.T_world_camera = gt[*i].T_world_camera;
      k.view = gasp::makeDepthView(frame->depth_m, frame->depth_intrinsics, pair.segment);
      places.add(keyframes.size(), gasp::describeKeyframe(k.view, pair));
      keyframes.push_back(std::move(k));
    }
    std::printf("keyframes: %zu (every %zu-th frame of %s)\n", keyframes.size(), input.every, sequence.describe().c_str());

    // Positives by the reference: some keyframe min_gap back shows 30 % of the query's depth.
    const auto truth = [&](std::size_t q, std::size_t c) -> std::optional<gasp::Isometry3> {
      if (!keyframes[q].T_world_camera || !keyframes[c].T_world_camera) return std::nullopt;
      return keyframes[c].T_world_camera->inverse() * *keyframes[q].T_world_camera;  // T_candidate_query
    };
    std::size_t positives = 0, queries = 0;
    std::vector<double> best_share(keyframes.size(), 0.0);
    for (std::size_t q = min_gap; q < keyframes.size(); ++q) {
      if (!keyframes[q].T_world_camera) continue;
      ++queries;
      for (std::size_t c = 0; c + min_gap <= q; ++c)
        if (const auto T = truth(q, c))
          best_share[q] = std::max(best_share[q], gasp::depthAgreement(keyframes[q].view, keyframes[c].view, *T, 4));
      positives += best_share[q] >= kPositiveShare ? 1 : 0;
    }

    // Detection: the nearest descriptors registered, the success with the most inliers.
    std::vector<Attempt> attempts;
    std::vector<gasp::eval::ScoredDetection> detections, consistent_detections;
    std::size_t wrong_detections_on_negatives = 0;
    for (std::size_t q = min_gap; q < keyframes.size(); ++q) {
      if (!keyframes[q].T_world_camera) continue;
      const gasp::PlaceDescriptor* d = places.find(q);
      std::optional<std::size_t> best;
      std::size_t rank = 0;
      if (d)
        for (const auto& [c, distance] : places.query(*d, candidates, [&](std::size_t id) { return id + min_gap > q; })) {
          Attempt a;
          a.query = q;
          a.candidate = c;
          a.rank = rank++;
          a.distance = distance;
          a.attempt = gasp::registerLoopClosure(keyframes[c].view, keyframes[q].view, keyframes[c].frame,
                                                keyframes[q].frame, true, pair, params.loop, a.constraint);
          if (const auto T = truth(q, c)) {
            a.share_truth = gasp::depthAgreement(keyframes[q].view, keyframes[c].view, *T, 4);
            if (a.attempt.inliers > 0) {
              const gasp::Isometry3 e = T->inverse() * a.constraint.T_from_to;
              a.t_err_m = gasp::translationNorm(e);
              a.r_err_deg = gasp::rotationAngle(e) * 180.0 / M_PI;
              a.correct = a.t_err_m <= gasp::eval::kWithinTranslationM && a.r_err_deg <= gasp::eval::kWithinRotationDeg;
              const gasp::Vector6 xi = gasp::leftPerturbation(a.constraint.T_from_to, *T);
              a.chi2 = xi.dot(a.constraint.information * xi);
              a.consistent = a.chi2 <= params.loop.gate_chi2;
            }
          }
          if (a.attempt.inliers > 0 && (!best || a.attempt.inliers > attempts[*best].attempt.inliers)) best = attempts.size();
          attempts.push_back(std::move(a));
        }
      if (!best) continue;
      const Attempt& b = attempts[*best];
      detections.push_back({static_cast<double>(b.attempt.inliers), b.correct});
      consistent_detections.push_back({static_cast<double>(b.attempt.inliers), b.consistent});
      if (!b.correct && best_share[q] < kPositiveShare) ++wrong_detections_on_negatives;
    }
    // A right pose can be found where the reference's share is just under 30 %: such a query
    // counts as a positive too (it had a loop to find), so that recall never exceeds 1.
    for (std::size_t q = min_gap; q < keyframes.size(); ++q) {
      if (best_share[q] >= kPositiveShare) continue;
      bool found = false;
      for (const Attempt& a : attempts) found = found || (a.query == q && (a.correct || a.consistent));
      if (found) ++positives;
    }

    const std::vector<gasp::eval::PrPoint> curve = gasp::eval::precisionRecallCurve(detections, positives);
    const std::vector<gasp::eval::PrPoint> consistent_curve =
        gasp::eval::precisionRecallCurve(consistent_detections, positives);
    std::size_t correct = 0, consistent = 0;
    for (const auto& d : detections) correct += d.correct ? 1 : 0;
    for (const auto& d : consistent_detections) consistent += d.correct ? 1 : 0;
    std::printf("queries: %zu (keyframes with a reference, at least %zu keyframes after the first)\n", queries, min_gap);
    std::printf("positives: %zu (an earlier keyframe shows >= %.0f %% of its depth at the reference pose, or a correct pose "
                "was found)\n",
                positives, 100 * kPositiveShare);
    std::printf("registrations: %zu (%zu candidates per query)\n", attempts.size(), candidates);
    std::printf("detections: %zu (%zu within 5 cm and 2 deg, %zu consistent with their information; %zu neither on "
                "queries without a loop)\n",
                detections.size(), correct, consistent, wrong_detections_on_negatives);
    for (const auto& [rule, c] : {std::pair{"within_5cm_2deg", &curve}, std::pair{"consistent", &consistent_curve}}) {
      // At the loop closer's own threshold, and the best threshold with no false detection.
      gasp::eval::PrPoint at_default;
      for (const auto& p : *c)
        if (p.threshold >= params.loop.relocalisation_min_inliers) at_default = p;
      std::printf("%s: at >= %d inliers precision %.3f, recall %.3f (%zu true, %zu false)", rule,
                  params.loop.relocalisation_min_inliers, at_default.precision, at_default.recall,
                  at_default.true_positives, at_default.false_positives);
      double full_threshold = 0.0;
      const double full_recall = gasp::eval::recallAtFullPrecision(*c, &full_threshold);
      if (std::isinf(full_threshold))
        std::printf("; recall at 100 %% precision 0 (no threshold keeps every detection true)\n");
      else
        std::printf("; recall at 100 %% precision %.3f (at >= %.0f inliers)\n", full_recall, full_threshold);
    }

    if (auto* f = outputs.find("--csv")) {
      f->stream() << "query_frame,candidate_frame,rank,descriptor_distance,inliers,accepted_by_min_inliers,t_err_m,r_err_deg,"
                     "chi2,correct,consistent,share_truth,query_best_share,reason\n";
      for (const Attempt& a : attempts) {
        std::string reason = a.attempt.reason;
        std::replace(reason.begin(), reason.end(), '"', '\'');
        f->stream() << gasp::formatted("%zu,%zu,%zu,%.4f,%d,%d,%.4f,%.3f,%.2f,%d,%d,%.3f,%.3f,\"", keyframes[a.query].frame,
                                       keyframes[a.candidate].frame, a.rank, a.distance, a.attempt.inliers,
                                       a.attempt.reason.empty() ? 1 : 0, a.t_err_m, a.r_err_deg, a.chi2, a.correct ? 1 : 0,
                                       a.consistent ? 1 : 0, a.share_truth, best_share[a.query])
                    << reason << "\"\n";
      }
      f->commit();
    }
    if (auto* f = outputs.find("--curve-csv")) {
      f->stream() << "rule,threshold,true_positives,false_positives,precision,recall\n";
      for (const auto& [rule, c] : {std::pair{"within_5cm_2deg", &curve}, std::pair{"consistent", &consistent_curve}})
        for (const auto& p : *c)
          f->stream() << gasp::formatted("%s,%.0f,%zu,%zu,%.4f,%.4f\n", rule, p.threshold, p.true_positives,
                                         p.false_positives, p.precision, p.recall);
      f->commit();
    }
    if (!drift.empty() && keyframes.size() < 3) {
      std::printf("drift: not possible: %zu keyframes, at least 3 are needed (a chain and its ATE)\n", keyframes.size());
      return 3;
    }
    if (!drift.empty()) {
      // The odometry chain: DepthOdometry over every frame from the first keyframe to the last,
      // its constraints composed between consecutive keyframes (with their covariance).
      gasp::DepthSequenceOptions every_frame = input;
      every_frame.every = 1;
      every_frame.first = keyframes.front().frame;
      every_frame.max_frames = keyframes.back().frame - keyframes.front().frame + 1;
      gasp::DepthSequence frames(every_frame);
      gasp::DepthOdometry odometry(params.odometry);
      std::vector<std::size_t> odometry_frame_of_input(keyframes.back().frame + 1, 0);
      while (auto f = frames.next()) {
        odometry_frame_of_input.at(frames.inputIndex()) = odometry.frames().size();
        odometry.addFrame(f->timestamp, f->depth_m, f->depth_intrinsics);
      }
      std::printf("odometry: %zu of %zu frames tracked (the chain's source)\n", odometry.trackedCount(),
                  odometry.frames().size());
      std::vector<gasp::PoseConstraint> chain;
      for (std::size_t i = 1; i < keyframes.size(); ++i) {
        const auto step = gasp::composeAlongTree(odometry.constraints(), odometry.frames().size(),
                                                 odometry_frame_of_input.at(keyframes[i - 1].frame),
                                                 odometry_frame_of_input.at(keyframes[i].frame));
        if (!step) {
          std::printf("drift: not possible: the odometry does not link frame %zu to frame %zu (it lost track)\n",
                      keyframes[i - 1].frame, keyframes[i].frame);
          return 3;
        }
        gasp::PoseConstraint c;
        c.from = i - 1;
        c.to = i;
        c.T_from_to = step->T_a_b;
        const gasp::Matrix6d S = 0.5 * (step->covariance + step->covariance.transpose());
        c.information = S.ldlt().solve(gasp::Matrix6d::Identity());
        chain.push_back(c);
      }
      // The same bend on every step: a turn about the camera's vertical (optical y) and a shift
      // along its x, so that the steps add up to about the drift asked for.
      const double n = static_cast<double>(chain.size());
      gasp::Vector6 bend;
      bend << drift[0] / n, 0.0, 0.0, 0.0, drift[1] * M_PI / 180.0 / n, 0.0;
      std::vector<gasp::PoseConstraint> bent = chain;
      for (gasp::PoseConstraint& c : bent) c.T_from_to = c.T_from_to * gasp::expLeft(bend);
      // Loop edges: every registration at or above the loop closer's threshold (no odometry gate).
      std::vector<gasp::PoseConstraint> closures;
      for (const Attempt& a : attempts) {
        if (!a.attempt.reason.empty()) continue;
        gasp::PoseConstraint c = a.constraint;
        c.from = a.candidate;
        c.to = a.query;
        closures.push_back(c);
      }
      gasp::Trajectory reference, undrifted, drifted, closed_undrifted, closed;
      const auto compose = [&](const std::vector<gasp::PoseConstraint>& steps) {
        std::vector<gasp::Isometry3> T{keyframes[0].T_world_camera.value_or(gasp::Isometry3::Identity())};
        for (const gasp::PoseConstraint& c : steps) T.push_back(T.back() * c.T_from_to);
        return T;
      };
      // Optimise, drop the closure the optimised graph contradicts most, again until none is.
      // Returns the optimised poses and how many closures were dropped.
      const auto close = [&](const std::vector<gasp::PoseConstraint>& steps) {
        std::vector<gasp::PoseConstraint> loops = closures;
        std::vector<gasp::Isometry3> T = compose(steps);
        for (;;) {
          std::vector<gasp::PoseConstraint> edges = steps;
          edges.insert(edges.end(), loops.begin(), loops.end());
          T = gasp::optimizePoseGraph(T, edges, params.graph).T_world_node;
          const auto worst = gasp::mostContradictedClosure(T, loops, params.loop.gate_chi2);
          if (!worst) break;
          loops.erase(loops.begin() + static_cast<std::ptrdiff_t>(worst->edge));
        }
        return std::pair{T, closures.size() - loops.size()};
      };
      const auto trajectoryOf = [&](const std::vector<gasp::Isometry3>& T) {
        gasp::Trajectory t;
        for (std::size_t i = 0; i < T.size(); ++i) t.push_back({keyframes[i].timestamp, T[i]});
        return t;
      };
      for (const Keyframe& k : keyframes)
        if (k.T_world_camera) reference.push_back({k.timestamp, *k.T_world_camera});
      const std::vector<gasp::Isometry3> T_chain = compose(chain), T_bent = compose(bent);
      const gasp::Isometry3 end = T_chain.back().inverse() * T_bent.back();
      std::printf("drift_injected: %.3f m, %.1f deg at the last keyframe (%zu steps)\n", gasp::translationNorm(end),
                  gasp::rotationAngle(end) * 180.0 / M_PI, chain.size());
      const auto ate = [&](const std::vector<gasp::Isometry3>& T) {
        return gasp::eval::computeAte(reference, trajectoryOf(T)).translation.rmse;
      };
      const double ate_chain = ate(T_chain), ate_bent = ate(T_bent);
      const auto [T_closed_chain, dropped_undrifted] = close(chain);
      const auto [T_closed_bent, dropped] = close(bent);
      const double ate_closed_chain = ate(T_closed_chain), ate_closed_bent = ate(T_closed_bent);
      std::printf("odometry_chain_ate_rmse_m: %.4f (with the drift: %.4f)\n", ate_chain, ate_bent);
      std::printf("closed_ate_rmse_m: %.4f (with the drift: %.4f); %zu loop edges at >= %d inliers, %zu (with the "
                  "drift: %zu) dropped as contradicted\n",
                  ate_closed_chain, ate_closed_bent, closures.size(), params.loop.relocalisation_min_inliers,
                  dropped_undrifted, dropped);
    }
  } catch (const std::exception& e) {
    std::cerr << "error: " << gasp::exceptionMessage(e) << '\n';
    return 1;
  }
  return 0;
}
