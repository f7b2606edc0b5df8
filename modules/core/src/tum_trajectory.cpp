#include "gasp/core/tum_trajectory.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <tuple>

#include "gasp/core/error.h"
#include "gasp/core/output_file.h"
#include "gasp/core/text_file.h"

namespace gasp {

Trajectory readTumTrajectory(const std::string& path) {
  Trajectory traj;
  forEachDataLine(path, [&](const std::string& line, int line_no) {
    const auto v = parseNumbers(line, path, line_no);
    if (v.size() != 8)
      throw Error(path + ":" + std::to_string(line_no) +
                  ": expected 8 numbers 'timestamp tx ty tz qx qy qz qw', got " +
                  std::to_string(v.size()));
    // Beyond 1e8 m (a thousand times the Earth's radius) differences of positions lose their
    // centimetres in double precision: not a trajectory GASP can evaluate.
    for (int k = 1; k <= 3; ++k)
      if (std::abs(v[k]) > 1e8)
        throw Error(path + ":" + std::to_string(line_no) + ": translation " + std::to_string(v[k]) +
                    " m is beyond 1e8 m: not a position");
    StampedPose p;
    p.timestamp = v[0];
    try {
      p.T_world_camera = poseFromTranslationQuaternion(v[1], v[2], v[3], v[4], v[5], v[6], v[7]);
    } catch (const Error& e) {
      throw Error(path + ":" + std::to_string(line_no) + ": " + e.what());
    }
    traj.push_back(p);
  });
  std::stable_sort(traj.begin(), traj.end(),
                   [](const StampedPose& a, const StampedPose& b) { return a.timestamp < b.timestamp; });
  for (std::size_t i = 1; i < traj.size(); ++i)
    if (traj[i].timestamp == traj[i - 1].timestamp)
      throw Error(path + ": timestamp " + std::to_string(traj[i].timestamp) + " appears twice");
  return traj;
}

void writeTumTrajectory(const std::string& path, const Trajectory& traj, const std::string& header) {
  OutputFile file(path, "trajectory");
  writeTumTrajectory(file.stream(), traj, header);
  file.commit();
}

void writeTumTrajectory(std::ostream& out, const Trajectory& traj, const std::string& header) {
  const auto flags = out.flags();
  const auto precision = out.precision();
  if (!header.empty()) out << "# " << header << '\n';
  out << "# timestamp tx ty tz qx qy qz qw\n";
  out << std::fixed;
  for (const auto& p : traj) {
    const Eigen::Quaterniond q(p.T_world_camera.linear());
    const Eigen::Vector3d t = p.T_world_camera.translation();
    out << std::setprecision(6) << p.timestamp << std::setprecision(9) << ' ' << t.x() << ' '
        << t.y() << ' ' << t.z() << ' ' << q.x() << ' ' << q.y() << ' ' << q.z() << ' ' << q.w()
        << '\n';
  }
  out.flags(flags);
  out.precision(precision);
}

std::size_t findClosestIndex(const std::vector<double>& sorted, double t) {
  if (sorted.empty()) throw Error("findClosestIndex: empty list");
  const auto it = std::lower_bound(sorted.begin(), sorted.end(), t);
  if (it == sorted.begin()) return 0;
  if (it == sorted.end()) return sorted.size() - 1;
  const std::size_t hi = static_cast<std::size_t>(it - sorted.begin());
  return (t - sorted[hi - 1] <= sorted[hi] - t) ? hi - 1 : hi;
}

std::optional<std::size_t> findNearest(const Trajectory& traj, double t, double max_dt) {
  if (traj.empty()) return std::nullopt;
  const auto it = std::lower_bound(traj.begin(), traj.end(), t,
                                   [](const StampedPose& p, double x) { return p.timestamp < x; });
  std::size_t best = traj.size();
  double best_dt = max_dt;
  auto consider = [&](std::size_t i) {
    const double dt = std::abs(traj[i].timestamp - t);
    if (dt <= best_dt) { best_dt = dt; best = i; }
  };
  const auto hi = static_cast<std::size_t>(it - traj.begin());
  if (hi < traj.size()) consider(hi);
  if (hi > 0) consider(hi - 1);
  if (best == traj.size()) return std::nullopt;
  return best;
}

std::vector<std::pair<std::size_t, std::size_t>> associateTimestamps(const std::vector<double>& a,
                                                                     const std::vector<double>& b,
                                                                     double max_dt, double offset) {
  // Candidates within the window, found through b sorted by time (same set as associate.py's
  // all-pairs scan), then taken greedily by (difference, a, b) as associate.py's tuple sort does.
  std::vector<std::size_t> b_order(b.size());
  for (std::size_t i = 0; i < b.size(); ++i) b_order[i] = i;
  std::sort(b_order.begin(), b_order.end(), [&](std::size_t x, std::size_t y) { return b[x] < b[y]; });
  std::vector<double> b_sorted(b.size());
  for (std::size_t i = 0; i < b.size(); ++i) b_sorted[i] = b[b_order[i]] + offset;

  std::vector<std::tuple<double, double, double, std::size_t, std::size_t>> candidates;
  for (std::size_t ia = 0; ia < a.size(); ++ia) {
    auto it = std::lower_bound(b_sorted.begin(), b_sorted.end(), a[ia] - max_dt);
    for (; it != b_sorted.end() && *it <= a[ia] + max_dt; ++it) {
      const std::size_t ib = b_order[static_cast<std::size_t>(it - b_sorted.begin())];
      const double diff = std::abs(a[ia] - (b[ib] + offset));
      if (diff < max_dt) candidates.emplace_back(diff, a[ia], b[ib], ia, ib);
    }
  }
  std::sort(candidates.begin(), candidates.end());
  std::vector<bool> used_a(a.size(), false), used_b(b.size(), false);
  std::vector<std::pair<std::size_t, std::size_t>> matches;
  for (const auto& c : candidates) {
    const std::size_t ia = std::get<3>(c), ib = std::get<4>(c);
    if (used_a[ia] || used_b[ib]) continue;
    used_a[ia] = used_b[ib] = true;
    matches.emplace_back(ia, ib);
  }
  std::sort(matches.begin(), matches.end(), [&](const auto& x, const auto& y) {
    return std::make_pair(a[x.first], b[x.second]) < std::make_pair(a[y.first], b[y.second]);
  });
  return matches;
}

}  // namespace gasp
