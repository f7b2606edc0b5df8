#include "gasp/graphslam/CGaspPoseGraphGSO.h"

#include <mrpt/config/CConfigFile.h>
#include <mrpt/system/filesystem.h>

#include <algorithm>
#include <chrono>
#include <iostream>
#include <set>
#include <sstream>
#include <utility>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/core/stopwatch.h"
#include "gasp/params/params_io.h"
#include "gasp/mrpt/pose_graph.h"
#include "gasp/rawlog/observation_conversion.h"
#include "gasp/slam/pose_graph.h"

namespace gasp::graphslam {

namespace {
const char* const kSection = "CGaspPoseGraphGSO";

/// Edges beyond a spanning tree: the loop closures of a connected graph.
std::size_t extraEdges(const Graph3D& g) {
  return g.edgeCount() + 1 > g.nodeCount() ? g.edgeCount() + 1 - g.nodeCount() : 0;
}

/// The graph's edges as node pairs, in the graph's (sorted) order.
std::vector<std::pair<std::size_t, std::size_t>> edgeKeys(const Graph3D& g) {
  std::vector<std::pair<std::size_t, std::size_t>> keys;
  keys.reserve(g.edges.size());
  for (const auto& e : g.edges) keys.emplace_back(e.first.first, e.first.second);
  return keys;
}
}  // namespace

CGaspPoseGraphGSO::CGaspPoseGraphGSO() {
  this->initializeLoggers(kSection);
  this->setMinLoggingLevel(mrpt::system::LVL_WARN);  // until loadParams() reads class_verbosity
}

void CGaspPoseGraphGSO::setSettings(const PoseGraphSettings& settings, double drop_chi2) {
  if (settings.max_iterations < 1) throw Error("CGaspPoseGraphGSO: max_iterations must be at least 1");
  if (!(settings.function_tolerance > 0.0)) throw Error("CGaspPoseGraphGSO: function_tolerance must be positive");
  if (!(drop_chi2 >= 0.0)) throw Error("CGaspPoseGraphGSO: drop_chi2 must be 0 (off) or positive");
  settings_ = settings;
  drop_chi2_ = drop_chi2;
}

bool CGaspPoseGraphGSO::updateState(mrpt::obs::CActionCollection::Ptr, mrpt::obs::CSensoryFrame::Ptr,
                                    mrpt::obs::CObservation::Ptr) {
  just_optimised_ = false;
  const std::size_t n = m_graph->nodeCount(), extra = extraEdges(*m_graph);
  // Closures added, or edges removed since the last look (e.g. by a loop closer that takes out
  // the rest of a relocalisation group whose vote this optimiser removed).
  auto keys = edgeKeys(*m_graph);
  const bool removed = !std::includes(keys.begin(), keys.end(), seen_edges_.begin(), seen_edges_.end());
  pending_ = pending_ || extra > seen_extra_edges_ || removed;
  seen_extra_edges_ = extra;
  seen_edges_ = std::move(keys);
  const bool new_node = n != seen_nodes_;
  seen_nodes_ = n;
  if (pending_ && !new_node) optimizeNow();
  return true;
}

void CGaspPoseGraphGSO::optimizeNow() {
  const auto t0 = std::chrono::steady_clock::now();
  pending_ = false;
  const std::size_t n = m_graph->nodeCount();
  if (n < 2) return;
  for (std::size_t i = 0; i < n; ++i)
    if (!m_graph->nodes.count(i)) throw Error("CGaspPoseGraphGSO: node IDs must be 0 .. N-1");
  std::vector<Isometry3> T_world_node(n);
  for (std::size_t i = 0; i < n; ++i) T_world_node[i] = fromCPose3D(m_graph->nodes.at(i));
  for (;;) {
    // Robot frames on both sides: the conversion is the identity mounting.
    std::vector<PoseConstraint> edges;
    std::vector<Graph3D::edges_map_t::iterator> where;
    skipped_ = 0;
    for (auto it = m_graph->edges.begin(); it != m_graph->edges.end(); ++it) {
      const auto [from, to] = it->first;
      if (from >= n || to >= n || from == to) throw Error("CGaspPoseGraphGSO: an edge names a node that is not in the graph");
      if (auto c = constraintFromEdge(from, to, it->second, Isometry3::Identity(), Isometry3::Identity())) {
        c->loop_closure = isClosureEdge(*m_graph, it);
        edges.push_back(*c);
        where.push_back(it);
      } else {
        ++skipped_;
      }
    }
    last_ = optimizePoseGraph(T_world_node, edges, settings_);
    ++optimisations_;
    T_world_node = last_.T_world_node;
    if (drop_chi2_ <= 0.0) break;
    const std::optional<Contradiction> contradiction = mostContradictedClosure(T_world_node, edges, drop_chi2_);
    if (!contradiction) break;
    const std::size_t worst = contradiction->edge;
    const double worst_chi2 = contradiction->chi2;
    MRPT_LOG_WARN_STREAM("edge " << edges[worst].from << " -> " << edges[worst].to
                                 << " removed: the optimised graph contradicts it (chi-square " << worst_chi2 << ")");
    m_graph->edges.erase(where[worst]);
    ++dropped_;
    if (after_removal_)
      if (const std::size_t more = after_removal_())
        MRPT_LOG_WARN_STREAM(more << " more edge(s) removed with it (the rest of its relocalisation)");
  }
  for (std::size_t i = 0; i < n; ++i) m_graph->nodes[i] = toCPose3D(T_world_node[i]);
  seen_extra_edges_ = extraEdges(*m_graph);
  seen_edges_ = edgeKeys(*m_graph);
  just_optimised_ = true;
  optimisation_ms_ += msSince(t0);
  MRPT_LOG_INFO_STREAM("optimised " << n << " nodes: chi-square " << last_.initial_chi2 << " -> " << last_.final_chi2);
}

void CGaspPoseGraphGSO::loadParams(const std::string& source_fname) {
  if (!mrpt::system::fileExists(source_fname))
    THROW_EXCEPTION_FMT("CGaspPoseGraphGSO: configuration file not found: %s", source_fname.c_str());
  const mrpt::config::CConfigFile cfg(source_fname);
  PoseGraphSettings s = settings_;
  readPoseGraphSettings(cfg, kSection, s, {"drop_chi2", "class_verbosity"});
  double drop = drop_chi2_;
  readValue(cfg, kSection, "drop_chi2", drop);
  int verbosity = static_cast<int>(getMinLoggingLevel());
  readValue(cfg, kSection, "class_verbosity", verbosity);
  try {
    setSettings(s, drop);
  } catch (const Error& e) {
    THROW_EXCEPTION_FMT("[%s]: %s", kSection, e.what());
  }
  setMinLoggingLevel(static_cast<mrpt::system::VerbosityLevel>(verbosity));
}

void CGaspPoseGraphGSO::printParams() const {
  std::cout << "------------[ CGaspPoseGraphGSO ]------------\n"
            << "max_iterations     = " << settings_.max_iterations << '\n'
            << "function_tolerance = " << settings_.function_tolerance << '\n'
            << "drop_chi2          = " << drop_chi2_ << '\n';
}

void CGaspPoseGraphGSO::getDescriptiveReport(std::string* report_str) const {
  CGraphSlamOptimizer<Graph3D>::getDescriptiveReport(report_str);
  std::ostringstream ss;
  ss << "GASP pose-graph optimiser (Ceres): " << optimisations_ << " optimisations, " << optimisation_ms_
     << " ms in all; edges removed: " << dropped_ << ", left out (no positive definite information): " << skipped_
     << '\n';
  if (optimisations_ > 0)
    ss << "last: chi-square " << last_.initial_chi2 << " -> " << last_.final_chi2 << ", " << last_.message << '\n';
  *report_str += ss.str();
}

}  // namespace gasp::graphslam
