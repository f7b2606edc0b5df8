#include "sequence_report.h"

#include <algorithm>
#include <cstdio>
#include <fstream>

#include "gasp/core/error.h"
#include "gasp/eval/ate.h"
#include "gasp/eval/error_statistics.h"
#include "gasp/eval/rpe.h"

namespace gasp::tools {

std::string trajectoryHeader(const std::string& what, const SequenceEnd& end) {
  if (end.complete) return what;
  return what + "\n# PARTIAL: the first " + std::to_string(end.frames) + " frames only; the input ended with an error: " +
         end.error;
}

int reportPartial(const SequenceEnd& end) {
  if (end.complete) return -1;
  std::printf("partial: %zu frames (the input ended with an error); the outputs hold these frames only\n", end.frames);
  std::fprintf(stderr, "error: %s\n", end.error.c_str());
  return 1;
}

void writeFramesCsv(std::ostream& out, const std::vector<OdometryFrame>& frames) {
  out << "index,timestamp,tracked,keyframe,reference,patches,inliers,deskewed,segmentation_ms,registration_ms,scene_change,partial,tracking_path,reason\n";
  for (const auto& f : frames) {
    std::string reason = f.reason;
    std::replace(reason.begin(), reason.end(), '"', '\'');
    char buf[200];
    std::snprintf(buf, sizeof buf, "%zu,%.6f,%d,%d,%zu,%d,%d,%d,%.2f,%.2f,%d,%d,%d,", f.index, f.timestamp, f.tracked ? 1 : 0,
                  f.keyframe ? 1 : 0, f.reference, f.patches, f.inliers, f.deskewed ? 1 : 0, f.segmentation_ms,
                  f.registration_ms, f.scene_change ? 1 : 0, f.partial ? 1 : 0, f.tracking_path ? 1 : 0);
    out << buf << '"' << reason << "\"\n";
  }
}

void printOdometrySummary(const DepthOdometry& odometry) {
  const auto& frames = odometry.frames();
  std::vector<double> seg, reg, total;
  for (const auto& f : frames)
    seg.push_back(f.segmentation_ms), reg.push_back(f.registration_ms), total.push_back(f.segmentation_ms + f.registration_ms);
  const auto median = [](const std::vector<double>& v) { return eval::computeStatistics(v).median; };
  std::printf("frames: %zu\n", frames.size());
  std::printf("tracked: %zu\n", odometry.trackedCount());
  std::string changed;  // the first frames taken through a scene change
  std::size_t listed = 0;
  for (const auto& f : frames)
    if (f.scene_change && listed++ < 10) changed += (changed.empty() ? "" : ", ") + std::to_string(f.index);
  if (listed > 10) changed += ", ...";
  std::printf("scene_changes: %zu%s\n", odometry.sceneChangeCount(),
              changed.empty() ? "" : (" (frames " + changed + ")").c_str());
  std::size_t partial = 0;
  for (const auto& f : frames) partial += f.partial ? 1 : 0;
  std::printf("partial_poses: %zu (tracked with free directions held by the motion prediction)\n", partial);
  std::size_t fast = 0, after_first = frames.empty() ? 0 : frames.size() - 1;
  for (const auto& f : frames) fast += f.tracking_path ? 1 : 0;
  std::printf("tracking_path: %zu of %zu frames (%.1f%%; the rest took the whole pipeline or were lost)\n", fast,
              after_first, after_first ? 100.0 * static_cast<double>(fast) / static_cast<double>(after_first) : 0.0);
  std::printf("keyframes: %zu\n", odometry.keyframeCount());
  std::printf("graph_components: %zu\n", odometry.componentCount());
  std::printf("median_ms_per_frame: %.1f (medians: segmentation %.1f, registration %.1f)\n", median(total), median(seg),
              median(reg));
}

void printThroughput(const std::vector<OdometryFrame>& frames, double wall_s) {
  if (frames.empty() || !(wall_s > 0.0)) return;
  // Sessions (DepthOdometry::startSession()) each have their own clock: their spans add up.
  std::vector<double> intervals;
  for (std::size_t i = 1; i < frames.size(); ++i)
    if (frames[i].session == frames[i - 1].session) intervals.push_back(frames[i].timestamp - frames[i - 1].timestamp);
  const double period = intervals.empty() ? 0.0 : eval::computeStatistics(intervals).median;
  double duration = 0.0;
  for (std::size_t first = 0, i = 1; i <= frames.size(); ++i)
    if (i == frames.size() || frames[i].session != frames[first].session) {
      duration += frames[i - 1].timestamp - frames[first].timestamp + period;
      first = i;
    }
  const double n = static_cast<double>(frames.size());
  std::printf("wall_time_s: %.2f\nfps: %.1f\n", wall_s, n / wall_s);
  if (duration > 0.0)
    std::printf("real_time_factor: %.2f (the sequence spans %.2f s)\n", duration / wall_s, duration);
}

void printEvaluation(const Trajectory& ground_truth, const Trajectory& estimate, std::size_t tracked,
                     const std::string& prefix) {
  if (ground_truth.empty()) return;
  if (tracked < 2) {
    std::printf("%sevaluation: not possible: %s\n", prefix.c_str(),
                tracked == 0 ? "no frame was tracked" : "no frame after the first was tracked (the other poses are predicted)");
    return;
  }
  try {
    const auto ate = eval::computeAte(ground_truth, estimate);
    std::printf("%sate_rmse_m: %.4f (%zu poses)\n", prefix.c_str(), ate.translation.rmse, ate.translation.count);
    const auto rpe = eval::computeRpe(ground_truth, estimate);
    std::printf("%srpe_1s_rmse: %.4f m, %.3f deg (%zu pairs)\n", prefix.c_str(), rpe.translation.rmse,
                rpe.rotation_deg.rmse, rpe.pairs.size());
  } catch (const Error& e) {
    std::printf("%sevaluation: not possible: %s\n", prefix.c_str(), e.what());
  }
}

}  // namespace gasp::tools
