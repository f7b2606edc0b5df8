#include "gasp/graphslam/graph_types.h"

#include <mrpt/obs/CActionRobotMovement3D.h>

#include <Eigen/Eigenvalues>

#include <iterator>

#include "gasp/rawlog/range_scan.h"

namespace gasp::graphslam {

mrpt::obs::CObservation3DRangeScan::Ptr depthScanOf(const mrpt::obs::CSensoryFrame::Ptr& observations,
                                                    const mrpt::obs::CObservation::Ptr& observation,
                                                    const std::string& sensor_label) {
  using mrpt::obs::CObservation3DRangeScan;
  // A LiDAR's sweep stored as a 3D scan of its points alone is no depth scan.
  const auto matches = [&](const CObservation3DRangeScan::Ptr& s) {
    return s && !isSweepObservation(*s) && (sensor_label.empty() || s->sensorLabel == sensor_label);
  };
  if (observation) {
    auto scan = std::dynamic_pointer_cast<CObservation3DRangeScan>(observation);
    return matches(scan) ? scan : nullptr;
  }
  if (!observations) return nullptr;
  for (const auto& o : *observations) {
    auto scan = std::dynamic_pointer_cast<CObservation3DRangeScan>(o);
    if (matches(scan)) return scan;
  }
  return nullptr;
}

mrpt::Clock::time_point stepTimestamp(const mrpt::obs::CActionCollection::Ptr& action,
                                      const mrpt::obs::CSensoryFrame::Ptr& observations,
                                      const mrpt::obs::CObservation::Ptr& observation) {
  if (observation) return observation->timestamp;
  if (action && action->size() > 0 && action->get(0)->timestamp != INVALID_TIMESTAMP) return action->get(0)->timestamp;
  if (observations)
    for (const auto& o : *observations)
      if (o && o->timestamp != INVALID_TIMESTAMP) return o->timestamp;
  return INVALID_TIMESTAMP;
}

mrpt::obs::CActionCollection::Ptr noMotionAction() {
  auto actions = std::make_shared<mrpt::obs::CActionCollection>();
  mrpt::obs::CActionRobotMovement3D still;  // zero pose change, INVALID_TIMESTAMP
  actions->insert(still);
  return actions;
}

namespace {

Eigen::Matrix<double, 6, 6> informationOf(const mrpt::poses::CPose3DPDFGaussianInf& edge) {
  Eigen::Matrix<double, 6, 6> I;
  for (int r = 0; r < 6; ++r)
    for (int k = 0; k < 6; ++k) I(r, k) = edge.cov_inv(r, k);
  return I;
}

}  // namespace

bool isBreakEdge(const mrpt::poses::CPose3DPDFGaussianInf& edge) {
  const Eigen::Matrix<double, 6, 6> I = informationOf(edge);
  if (!I.allFinite()) return true;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eig(0.5 * (I + I.transpose()), Eigen::EigenvaluesOnly);
  return eig.eigenvalues().maxCoeff() < kBreakMaxInformation;
}

std::size_t breakNonFiniteEdges(Graph3D& graph) {
  std::size_t n = 0;
  for (auto& [ids, edge] : graph.edges) {
    if (informationOf(edge).allFinite()) continue;
    edge.cov_inv.setIdentity();
    edge.cov_inv *= kBreakInformation;
    ++n;
  }
  return n;
}

bool isClosureEdge(const Graph3D& graph, Graph3D::edges_map_t::const_iterator it) {
  const auto [from, to] = it->first;
  if (to != from + 1) return true;
  return it != graph.edges.begin() && std::prev(it)->first == it->first;
}

Graph3D::edges_map_t::const_iterator findEdge(const Graph3D& graph, std::size_t from, std::size_t to,
                                              const mrpt::poses::CPose3DPDFGaussianInf& edge) {
  const auto [first, last] = graph.edges.equal_range({from, to});
  for (auto it = first; it != last; ++it)
    if (it->second.mean.getHomogeneousMatrixVal<mrpt::math::CMatrixDouble44>().asEigen() ==
            edge.mean.getHomogeneousMatrixVal<mrpt::math::CMatrixDouble44>().asEigen() &&
        informationOf(it->second) == informationOf(edge))
      return it;
  return graph.edges.end();
}

}  // namespace gasp::graphslam
