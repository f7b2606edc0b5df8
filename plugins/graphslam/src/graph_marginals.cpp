#include "gasp/graphslam/graph_marginals.h"

#include <string>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/mrpt/pose_graph.h"
#include "gasp/rawlog/observation_conversion.h"

namespace gasp::graphslam {

PoseGraphMarginals graphMarginals(const Graph3D& graph) {
  const std::size_t n = graph.nodeCount();
  std::vector<Isometry3> T_world_node(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto it = graph.nodes.find(i);
    if (it == graph.nodes.end()) throw Error("graph marginals: node IDs must be 0 .. N-1");
    T_world_node[i] = fromCPose3D(it->second);
  }
  std::vector<PoseConstraint> edges;
  for (auto it = graph.edges.begin(); it != graph.edges.end(); ++it) {
    const auto [from, to] = it->first;
    if (from >= n || to >= n) throw Error("graph marginals: an edge names a node that is not in the graph");
    if (from == to || isBreakEdge(it->second)) continue;
    // Robot frames on both sides: the conversion is the identity mounting.
    if (auto c = constraintFromEdge(from, to, it->second, Isometry3::Identity(), Isometry3::Identity()))
      edges.push_back(*c);
  }
  return poseGraphMarginals(T_world_node, edges);
}

}  // namespace gasp::graphslam
