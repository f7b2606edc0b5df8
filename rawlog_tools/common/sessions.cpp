#include "sessions.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <optional>
#include <regex>

#include "gasp/core/error.h"
#include "gasp/core/format.h"
#include "gasp/eval/ate.h"

namespace gasp::tools {

DepthSequenceOptions sessionOptions(const std::string& spec, const DepthSequenceOptions& shared) {
  DepthSequenceOptions o = shared;
  std::string path = spec;
  static const std::regex range(R"(^(.*)@([0-9]+)-([0-9]*)$)");
  std::smatch m;
  if (std::regex_match(spec, m, range)) {
    path = m[1];
    const auto index = [&spec](const std::string& digits) -> std::size_t {
      if (digits.size() > 9) throw Error("session " + spec + ": a frame index beyond 999999999");
      return std::stoul(digits);
    };
    const std::size_t first = index(m[2]);
    o.first = first;
    o.max_frames = 0;
    if (m[3].length() > 0) {
      const std::size_t last = index(m[3]);
      if (last < first) throw Error("session " + spec + ": the last frame comes before the first (expected PATH@FIRST-LAST)");
      o.max_frames = (last - first) / std::max<std::size_t>(o.every, 1) + 1;
    }
  } else if (const std::size_t at = spec.rfind('@'); at != std::string::npos) {
    // A '@' may belong to the path; one followed by digits and dashes only meant a range.
    const std::string tail = spec.substr(at + 1);
    const bool range_like = !tail.empty() && std::all_of(tail.begin(), tail.end(), [](char c) {
      return std::isdigit(static_cast<unsigned char>(c)) || c == '-';
    });
    if (range_like) throw Error("session " + spec + ": expected PATH@FIRST-LAST (frame indices, LAST optional)");
  }
  if (path.empty()) throw Error("session " + spec + ": no input path");
  o.tum_dir.clear();
  o.rawlog_path.clear();
  // A folder is a TUM sequence; anything else a rawlog (DepthSequence says when it is neither).
  if (std::filesystem::is_directory(path))
    o.tum_dir = path;
  else
    o.rawlog_path = path;
  return o;
}

std::string sessionPath(const std::string& path, std::size_t session, std::size_t count) {
  if (count <= 1 || path.empty()) return path;
  const std::filesystem::path p(path);
  std::filesystem::path out = p;
  out.replace_filename(p.stem().string() + ".session" + std::to_string(session + 1) + p.extension().string());
  return out.string();
}

std::vector<std::vector<std::size_t>> sessionMaps(const std::vector<std::vector<std::size_t>>& links) {
  const std::size_t n = links.size();
  std::vector<std::size_t> map_of(n, n);  // n: not assigned yet
  std::vector<std::vector<std::size_t>> maps;
  for (std::size_t s = 0; s < n; ++s) {
    if (map_of[s] != n) continue;
    std::vector<std::size_t> members{s}, stack{s};
    map_of[s] = maps.size();
    while (!stack.empty()) {
      const std::size_t a = stack.back();
      stack.pop_back();
      for (std::size_t b = 0; b < n; ++b)
        if (links[a][b] > 0 && map_of[b] == n) {
          map_of[b] = maps.size();
          members.push_back(b);
          stack.push_back(b);
        }
    }
    std::sort(members.begin(), members.end());
    maps.push_back(members);
  }
  return maps;
}

Trajectory sessionTrajectory(const Trajectory& all, const SessionRun& run) {
  const auto begin = all.begin() + static_cast<std::ptrdiff_t>(std::min(run.first_frame, all.size()));
  const auto end = all.begin() + static_cast<std::ptrdiff_t>(std::min(run.first_frame + run.frames, all.size()));
  return Trajectory(begin, end);
}

namespace {

/// A map's ATE: one alignment over the map's sessions, told apart by shifting each one's
/// timestamps (reference and estimate alike) to begin 1000 s after the previous one's end.
struct MapAte {
  std::vector<double> session_rmse;  ///< per session (NaN: not in the map, or no reference)
  double rmse = std::nan("");        ///< over all of the map's sessions
  std::size_t poses = 0;
  std::string message;  ///< why there is none
};

MapAte ateInMapFrame(const std::vector<std::size_t>& map, const std::vector<SessionRun>& runs,
                     const Trajectory& trajectory) {
  Trajectory gt, est;
  std::vector<std::size_t> est_session;
  double end = 0.0;  // the shifted timestamps so far end before this
  for (const std::size_t s : map) {
    if (runs[s].ground_truth.empty()) continue;
    const Trajectory mine = sessionTrajectory(trajectory, runs[s]);
    double lo = runs[s].ground_truth.front().timestamp, hi = lo;
    for (const Trajectory* t : {&runs[s].ground_truth, &mine})
      for (const StampedPose& p : *t) lo = std::min(lo, p.timestamp), hi = std::max(hi, p.timestamp);
    const double shift = end - lo;
    end = hi + shift + 1000.0;
    for (StampedPose p : runs[s].ground_truth) {
      p.timestamp += shift;
      gt.push_back(p);
    }
    for (StampedPose p : mine) {
      p.timestamp += shift;
      est.push_back(p);
      est_session.push_back(s);
    }
  }
  MapAte out;
  out.session_rmse.assign(runs.size(), std::nan(""));
  try {
    const eval::AteResult ate = eval::computeAte(gt, est);
    out.rmse = ate.translation.rmse;
    out.poses = ate.translation.count;
    std::vector<double> sum(runs.size(), 0.0);
    std::vector<std::size_t> count(runs.size(), 0);
    for (std::size_t i = 0; i < ate.matches.size(); ++i) {
      const std::size_t s = est_session[ate.matches[i].second];
      sum[s] += ate.errors[i] * ate.errors[i];
      ++count[s];
    }
    for (const std::size_t s : map)
      if (count[s] > 0) out.session_rmse[s] = std::sqrt(sum[s] / static_cast<double>(count[s]));
  } catch (const Error& e) {
    out.message = e.what();
  }
  return out;
}

/// The session's own ATE RMSE (aligned on its own), NaN without a reference or an alignment.
double ownAte(const SessionRun& run, const Trajectory& trajectory) {
  if (run.ground_truth.empty() || run.tracked < 2) return std::nan("");
  try {
    return eval::computeAte(run.ground_truth, sessionTrajectory(trajectory, run)).translation.rmse;
  } catch (const Error&) {
    return std::nan("");
  }
}

/// A YAML double-quoted string.
std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + '"';
}

}  // namespace

void reportSessions(const std::vector<SessionRun>& runs, const DepthSlam& slam, const Trajectory& trajectory,
                    const std::vector<std::string>& trajectory_paths, std::ostream* yaml) {
  // The links between runs: a run that gave no frame is no session of the odometry's.
  const std::vector<std::vector<std::size_t>> session_links = slam.sessionLinks();
  const std::vector<OdometryFrame>& frames = slam.odometry().frames();
  const auto sessionOf = [&](const SessionRun& r) -> std::optional<std::size_t> {
    if (r.frames == 0 || r.first_frame >= frames.size()) return std::nullopt;
    return frames[r.first_frame].session;
  };
  std::vector<std::vector<std::size_t>> links(runs.size(), std::vector<std::size_t>(runs.size(), 0));
  for (std::size_t a = 0; a < runs.size(); ++a)
    for (std::size_t b = 0; b < runs.size(); ++b) {
      const auto sa = sessionOf(runs[a]), sb = sessionOf(runs[b]);
      if (sa && sb && *sa < session_links.size() && *sb < session_links.size()) links[a][b] = session_links[*sa][*sb];
    }
  const std::vector<std::vector<std::size_t>> maps = sessionMaps(links);
  std::vector<std::size_t> map_of(runs.size(), 0);
  for (std::size_t m = 0; m < maps.size(); ++m)
    for (const std::size_t s : maps[m]) map_of[s] = m;
  std::vector<double> in_map(runs.size(), std::nan(""));
  std::vector<MapAte> map_ate(maps.size());
  for (std::size_t m = 0; m < maps.size(); ++m) {
    if (maps[m].size() < 2) continue;
    map_ate[m] = ateInMapFrame(maps[m], runs, trajectory);
    for (const std::size_t s : maps[m]) in_map[s] = map_ate[m].session_rmse.empty() ? std::nan("") : map_ate[m].session_rmse[s];
  }

  std::printf("sessions: %zu in %zu map%s\n", runs.size(), maps.size(), maps.size() == 1 ? "" : "s");
  if (yaml) *yaml << "sessions:\n";
  for (std::size_t s = 0; s < runs.size(); ++s) {
    const SessionRun& r = runs[s];
    std::string joined;
    for (std::size_t b = 0; b < runs.size(); ++b)
      if (links[s][b] > 0) joined += formatted("%s%zu (%zu constraints)", joined.empty() ? "" : ", ", b + 1, links[s][b]);
    const double own = ownAte(r, trajectory);
    const std::string span = r.frames == 0 ? "no frame" : formatted("frames %zu-%zu", r.first_frame, r.first_frame + r.frames - 1);
    std::printf("session %zu: %s: %s, %zu of %zu tracked%s; map %zu; joined to %s; trajectory %s\n", s + 1,
                r.input.c_str(), span.c_str(), r.tracked, r.frames,
                r.end.complete ? "" : " (PARTIAL: the input ended with an error)", map_of[s] + 1,
                joined.empty() ? "none" : joined.c_str(), trajectory_paths[s].c_str());
    if (!std::isnan(own))
      std::printf("session %zu: ate_rmse_m: %.4f (aligned alone)%s\n", s + 1, own,
                  std::isnan(in_map[s]) ? "" : formatted(", %.4f in its map's frame", in_map[s]).c_str());
    if (!yaml) continue;
    *yaml << "  - session: " << s + 1 << "\n    input: " << quoted(r.input) << "\n    first_frame: " << r.first_frame
          << "\n    frames: " << r.frames << "\n    tracked: " << r.tracked
          << "\n    complete: " << (r.end.complete ? "true" : "false") << "\n    map: " << map_of[s] + 1
          << "\n    trajectory: " << quoted(trajectory_paths[s]) << "\n    joined_to: {";
    bool first = true;
    for (std::size_t b = 0; b < runs.size(); ++b)
      if (links[s][b] > 0) {
        *yaml << (first ? "" : ", ") << b + 1 << ": " << links[s][b];
        first = false;
      }
    *yaml << "}\n";
    if (!std::isnan(own)) *yaml << formatted("    ate_rmse_m: %.6f\n", own);
    if (!std::isnan(in_map[s])) *yaml << formatted("    ate_rmse_m_in_map_frame: %.6f\n", in_map[s]);
  }
  if (yaml) *yaml << "maps:\n";
  for (std::size_t m = 0; m < maps.size(); ++m) {
    std::string members;
    for (const std::size_t s : maps[m]) members += formatted("%s%zu", members.empty() ? "" : ", ", s + 1);
    std::printf("map %zu: session%s %s%s\n", m + 1, maps[m].size() == 1 ? "" : "s", members.c_str(),
                maps[m].size() == 1 ? " alone: no constraint joins it to another; its trajectory is in the world it started in"
                                    : formatted(" joined; in the world session %zu started in", maps[m].front() + 1).c_str());
    if (!map_ate[m].message.empty())
      std::printf("map %zu: evaluation: not possible: %s\n", m + 1, map_ate[m].message.c_str());
    else if (!std::isnan(map_ate[m].rmse))
      std::printf("map %zu: ate_rmse_m: %.4f (%zu poses, one alignment over its sessions)\n", m + 1, map_ate[m].rmse,
                  map_ate[m].poses);
    if (!yaml) continue;
    *yaml << "  - sessions: [" << members << "]\n";
    if (!std::isnan(map_ate[m].rmse)) *yaml << formatted("    ate_rmse_m: %.6f\n", map_ate[m].rmse);
  }
}

}  // namespace gasp::tools
