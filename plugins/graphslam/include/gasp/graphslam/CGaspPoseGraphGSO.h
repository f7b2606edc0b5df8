#pragma once
/// \file CGaspPoseGraphGSO.h mrpt::graphslam optimiser (GSO): the whole graph optimised with
/// GASP's Ceres pose-graph optimiser (gasp/slam/pose_graph_optimizer.h).
///
/// Each edge's information is read as MRPT's CPose3DPDFGaussianInf declares it, over
/// [x y z yaw pitch roll], and converted to the left perturbation the optimiser uses (first
/// order). (MRPT 2.5.8's CLevMarqGSO applies it to SE(3)'s logarithm [x y z rx ry rz] instead.)
///
/// When: CGraphSlamEngine recomputes every node's pose along a spanning tree from the root
/// (dijkstra_nodes_estimate) after each step that registers a node, after the optimiser has run,
/// so an optimisation in such a step would be lost. This optimiser therefore runs at the first
/// step without a new node after edges beyond the node registration decider's (loop closures)
/// were added or any edge was removed, and when optimizeNow() is called (gasp-graphslam calls it
/// after the last step, so the graph it saves is optimised).
///
/// After each optimisation, a closure (isClosureEdge(): an edge between nodes that are not
/// consecutive, or a second edge between consecutive ones) whose chi-square at the optimised
/// poses exceeds `drop_chi2` is removed, the worst first, and the graph optimised again
/// (0 = never). After each removal the hook of setAfterEdgeRemoval() runs, before the graph is
/// optimised again: gasp-graphslam gives it CGaspLoopClosureERD::syncWithGraph(), so the other
/// votes of a relocalisation take no part in that optimisation (as in DepthSlam).
///
/// Parameters: ini section [CGaspPoseGraphGSO]: max_iterations, function_tolerance, drop_chi2,
/// class_verbosity.
#include <mrpt/graphslam/interfaces/CGraphSlamOptimizer.h>

#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "gasp/graphslam/graph_types.h"
#include "gasp/slam/pose_graph_optimizer.h"

namespace gasp::graphslam {

class CGaspPoseGraphGSO : public mrpt::graphslam::optimizers::CGraphSlamOptimizer<Graph3D> {
 public:
  CGaspPoseGraphGSO();

  bool updateState(mrpt::obs::CActionCollection::Ptr action, mrpt::obs::CSensoryFrame::Ptr observations,
                   mrpt::obs::CObservation::Ptr observation) override;
  void loadParams(const std::string& source_fname) override;
  void printParams() const override;
  void getDescriptiveReport(std::string* report_str) const override;
  bool justFullyOptimizedGraph() const override { return just_optimised_; }

  /// Optimises the graph now (the caller holds the graph's lock, if it shares the graph).
  void optimizeNow();

  /// Runs after this optimiser removes an edge and before it optimises again; may remove further
  /// edges from the graph (it returns how many, for the log). Empty: none.
  void setAfterEdgeRemoval(std::function<std::size_t()> hook) { after_removal_ = std::move(hook); }

  void setSettings(const PoseGraphSettings& settings, double drop_chi2);
  const PoseGraphSettings& settings() const { return settings_; }
  double dropChi2() const { return drop_chi2_; }
  std::size_t optimisations() const { return optimisations_; }
  std::size_t droppedEdges() const { return dropped_; }
  /// Edges left out because their information is not positive definite.
  std::size_t skippedEdges() const { return skipped_; }
  double optimisationMs() const { return optimisation_ms_; }
  /// The last optimisation's result (chi-square before and after, Ceres's summary).
  const PoseGraphResult& lastResult() const { return last_; }

 protected:
  void optimizeGraph() override { optimizeNow(); }

 private:
  PoseGraphSettings settings_;
  double drop_chi2_ = 22.46;  ///< the loop closer's gate (chi-square of 6 d.o.f. at 0.999)
  std::size_t seen_nodes_ = 0, seen_extra_edges_ = 0;
  std::vector<std::pair<std::size_t, std::size_t>> seen_edges_;  ///< edge keys at the last look
  bool pending_ = false, just_optimised_ = false;
  std::size_t optimisations_ = 0, dropped_ = 0, skipped_ = 0;
  double optimisation_ms_ = 0.0;
  PoseGraphResult last_;
  std::function<std::size_t()> after_removal_;
};

}  // namespace gasp::graphslam
