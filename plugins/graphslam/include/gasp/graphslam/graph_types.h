#pragma once
/// \file graph_types.h What GASP's mrpt::graphslam classes share: the graph type (3D poses with
/// information matrices), the depth observation of a step, and how a "break" edge is told.
#include <mrpt/graphs/CNetworkOfPoses.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CObservation.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose3DPDFGaussianInf.h>

#include <string>

namespace gasp::graphslam {

/// The graph GASP's deciders and optimiser work on: CGraphSlamEngine<Graph3D>.
using Graph3D = mrpt::graphs::CNetworkOfPoses3DInf;

/// The 3D range scan of an engine step: `observation` (rawlog format #2) or the first scan of
/// `observations` (format #1) whose sensorLabel is `sensor_label` (empty: any). nullptr without one.
mrpt::obs::CObservation3DRangeScan::Ptr depthScanOf(const mrpt::obs::CSensoryFrame::Ptr& observations,
                                                    const mrpt::obs::CObservation::Ptr& observation,
                                                    const std::string& sensor_label);

/// The time of an engine step as CGraphSlamEngine reads it: `observation`'s (format #2), else the
/// first action's, else the first valid one of `observations`' (INVALID_TIMESTAMP when none).
mrpt::Clock::time_point stepTimestamp(const mrpt::obs::CActionCollection::Ptr& action,
                                      const mrpt::obs::CSensoryFrame::Ptr& observations,
                                      const mrpt::obs::CObservation::Ptr& observation);

/// For a sensory frame without an action (rawlog format #1 as GASP's tools write it): one
/// CActionRobotMovement3D with no motion and no timestamp. CGraphSlamEngine reads the first
/// action of every format-#1 step (its timestamp, then the sensory frame's; its motion as
/// odometry) and fails on an empty collection.
mrpt::obs::CActionCollection::Ptr noMotionAction();

/// A break edge keeps MRPT's graph connected where GASP's odometry lost track (CGraphSlamEngine
/// computes node poses along a spanning tree from the root, so every node needs a path to it).
/// It carries the odometry's prediction with this information on each of [x y z yaw pitch roll]
/// (a standard deviation of 1000 m and 1000 rad): it constrains nothing.
constexpr double kBreakInformation = 1e-6;
/// Edges whose information has no eigenvalue above this are breaks: the loop closer does not
/// count them as links between nodes, and they predict nothing for its gate.
constexpr double kBreakMaxInformation = 1e-3;
/// True for a break edge (kBreakMaxInformation), and for an edge whose information is not finite
/// (MRPT 2.5.8's CFixedIntervalsNRD gives its first edge NaN information): it constrains nothing
/// that can be used.
bool isBreakEdge(const mrpt::poses::CPose3DPDFGaussianInf& edge);

/// Gives every edge of `graph` whose information is not finite the information of a break edge
/// (kBreakInformation on the diagonal), keeping its mean; returns how many. For graph files
/// (VERTEX3 / EDGE3) that other tools can read: `nan` is no information matrix.
std::size_t breakNonFiniteEdges(Graph3D& graph);

/// Whether the edge at `it` is a closure (an edge beyond the node registration decider's): it
/// links nodes that are not consecutive, or it is not the first edge between its two
/// consecutive nodes. The node decider inserts its edge i -> i+1 in the step that adds node i+1,
/// before any edge decider can name that node, and std::multimap keeps equal keys in insertion
/// order; a later edge between the same nodes is a relocalisation across a break.
bool isClosureEdge(const Graph3D& graph, Graph3D::edges_map_t::const_iterator it);

/// The edge from -> to of `graph` that equals `edge` exactly (mean and information): how a
/// decider finds its own edge among others between the same nodes. end() when there is none.
Graph3D::edges_map_t::const_iterator findEdge(const Graph3D& graph, std::size_t from, std::size_t to,
                                              const mrpt::poses::CPose3DPDFGaussianInf& edge);

}  // namespace gasp::graphslam
