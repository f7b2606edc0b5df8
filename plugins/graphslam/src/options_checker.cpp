#include "gasp/graphslam/options_checker.h"

#include <algorithm>
#include <memory>

#include "gasp/graphslam/CGaspLoopClosureERD.h"
#include "gasp/graphslam/CGaspOdometryNRD.h"
#include "gasp/graphslam/CGaspPoseGraphGSO.h"

namespace gasp::graphslam {

GaspOptionsChecker::GaspOptionsChecker() {
  createDeciderOptimizerMappings();  // MRPT's, then _createDeciderOptimizerMappings()
  populateDeciderOptimizerProperties();
}

void GaspOptionsChecker::_createDeciderOptimizerMappings() {
  node_regs_map["CGaspOdometryNRD"] = &createNodeRegistrationDecider<CGaspOdometryNRD>;
  edge_regs_map["CGaspLoopClosureERD"] = &createEdgeRegistrationDecider<CGaspLoopClosureERD>;
  optimizers_map["CGaspPoseGraphGSO"] = &createGraphSlamOptimizer<CGaspPoseGraphGSO>;
  // MRPT 2.5.8 maps "CEmptyGSO" to CLevMarqGSO (its CEmptyGSO is abstract): not offered under a
  // name that promises no optimisation.
  optimizers_map.erase("CEmptyGSO");
}

void GaspOptionsChecker::populateDeciderOptimizerProperties() {
  using mrpt::graphslam::apps::TOptimizerProps;
  using mrpt::graphslam::apps::TRegistrationDeciderProps;
  TUserOptionsChecker<Graph3D>::populateDeciderOptimizerProperties();
  for (auto it = optimizers_descriptions.begin(); it != optimizers_descriptions.end();) {
    if ((*it)->name != "CEmptyGSO") {
      ++it;
      continue;
    }
    delete *it;  // owned by the base class's vector
    it = optimizers_descriptions.erase(it);
  }
  // MRPT describes its 2D-only deciders too (CICPCriteriaNRD, CICPCriteriaERD, CLoopCloserERD),
  // which the 3D maps above do not hold: --list-regs must not offer them.
  for (auto it = regs_descriptions.begin(); it != regs_descriptions.end();) {
    const bool in_3d = node_regs_map.count((*it)->name) > 0 || edge_regs_map.count((*it)->name) > 0;
    if (in_3d) {
      ++it;
      continue;
    }
    delete *it;  // owned by the base class's vector
    it = regs_descriptions.erase(it);
  }
  // The base class owns and deletes the descriptions.
  auto node = std::make_unique<TRegistrationDeciderProps>();
  node->name = "CGaspOdometryNRD";
  node->description =
      "A node per keyframe of GASP's depth odometry (superpixel association without appearance, RANSAC and "
      "point-to-plane refinement); edges carry GASP's information. World = the first keyframe's robot frame";
  node->type = "Node";
  node->rawlog_format = "Both";
  node->observations_used = {"CObservation3DRangeScan - Format #1, #2"};
  node->is_slam_2d = false;
  node->is_slam_3d = true;
  regs_descriptions.push_back(node.release());

  auto edge = std::make_unique<TRegistrationDeciderProps>();
  edge->name = "CGaspLoopClosureERD";
  edge->description =
      "GASP loop closures (no initial guess) between a new node and nearby earlier nodes, gated by the prediction "
      "along the node decider's edges; relocalisation across breaks. Works with any node decider";
  edge->type = "Edge";
  edge->rawlog_format = "Both";
  edge->observations_used = {"CObservation3DRangeScan - Format #1, #2"};
  edge->is_slam_2d = false;
  edge->is_slam_3d = true;
  regs_descriptions.push_back(edge.release());

  auto opt = std::make_unique<TOptimizerProps>();
  opt->name = "CGaspPoseGraphGSO";
  opt->description =
      "The whole graph optimised with Ceres (quaternion manifold), information read over [x y z yaw pitch roll]; "
      "contradicted loop closures removed";
  opt->is_slam_2d = false;
  opt->is_slam_3d = true;
  optimizers_descriptions.push_back(opt.release());
}

}  // namespace gasp::graphslam
