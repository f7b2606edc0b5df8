#pragma once
/// \file CGaspLoopClosureERD.h mrpt::graphslam edge registration decider (ERD): GASP loop
/// closures and relocalisations between the graph's nodes, with any node registration decider.
///
/// Each node gets the depth scan of the step that registered it (the root: the first scan with
/// surface patches, as the odometry's origin), which
/// is segmented once and kept. For each new node, GASP registers it with no initial guess to
/// earlier nodes chosen as gasp-slam chooses keyframes (loop_closure.h): nearby nodes of the same
/// piece of the graph, and the latest nodes of other pieces (relocalisation). A loop closure is
/// inserted when it agrees with the prediction along the node registration decider's edges (the
/// edges i -> i+1) within both uncertainties (a chi-square gate); a relocalisation needs more
/// inliers, and joins two pieces once relocalisation_agreeing of them agree (relocalisation.h). Break edges (graph_types.h) do not join pieces. Inserted edges: the registration's
/// pose between the robot frames with GASP's edge information in [x y z yaw pitch roll].
///
/// Parameters: ini section [CGaspLoopClosureERD] (docs/graphslam.md): the pair keys of
/// params_io.h (whose min_inliers is RANSAC's), search_radius_m, max_axis_angle_deg,
/// min_keyframe_gap (at least 2), max_candidates, loop_min_inliers, gate_chi2, relocalisation_candidates, relocalisation_min_inliers,
/// relocalisation_agreeing, sensor_label, class_verbosity.
#include <mrpt/graphslam/interfaces/CEdgeRegistrationDecider.h>

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "gasp/association/place_descriptor.h"
#include "gasp/graphslam/CGaspOdometryNRD.h"
#include "gasp/graphslam/graph_types.h"
#include "gasp/odometry/pose_constraint.h"
#include "gasp/pipeline/depth_view.h"
#include "gasp/pipeline/pair_registration.h"
#include "gasp/slam/loop_closure.h"
#include "gasp/slam/relocalisation.h"
#include "gasp/slam/slam_params.h"

namespace gasp::graphslam {

class CGaspLoopClosureERD : public mrpt::graphslam::deciders::CEdgeRegistrationDecider<Graph3D> {
 public:
  CGaspLoopClosureERD();

  /// Keeps the step's scan; when the graph gained nodes, segments the newest one's scan and
  /// registers it to its candidates, inserting the closures taken. Always true.
  bool updateState(mrpt::obs::CActionCollection::Ptr action, mrpt::obs::CSensoryFrame::Ptr observations,
                   mrpt::obs::CObservation::Ptr observation) override;
  /// Reads section [CGaspLoopClosureERD] (as CGaspOdometryNRD::loadParams()).
  void loadParams(const std::string& source_fname) override;
  void printParams() const override;
  void getDescriptiveReport(std::string* report_str) const override;
  /// "lc": loop closures and relocalisations inserted.
  void getEdgesStats(std::map<std::string, int>* edge_type_to_num) const override;

  /// Throws gasp::Error for invalid parameters (and a min_keyframe_gap below 2).
  void setParams(const PairParams& pair, const LoopClosureParams& loop);
  const PairParams& pairParams() const { return pair_; }
  const LoopClosureParams& loopParams() const { return loop_; }
  void setSensorLabel(const std::string& label) { sensor_label_ = label; }
  /// The 3D range scans used: those with this sensorLabel (empty: the first of any step).
  const std::string& sensorLabel() const { return sensor_label_; }
  /// Every registration tried, in order (from, to: node IDs); `accepted` while its edge is in
  /// the graph (as of the last syncWithGraph()).
  const std::vector<LoopClosureAttempt>& attempts() const { return attempts_; }
  /// Loop closures and relocalisations in the graph (as of the last syncWithGraph()).
  std::size_t insertedEdges() const { return closures_.size(); }
  /// With GASP's node decider in the same engine: each node takes the segmented view its
  /// keyframe was registered with (deskewed when it was) instead of segmenting the scan again,
  /// when both segment with the same parameters and use the same sensor_label (else the loop
  /// closer segments as without it).
  /// `node_decider` must outlive this decider; nullptr unlinks. gasp-graphslam links the two.
  void useKeyframeViewsOf(const CGaspOdometryNRD* node_decider) { node_decider_ = node_decider; }
  /// Scans this decider segmented itself (the rest were its node decider's keyframe views).
  std::size_t segmentations() const { return segmentations_; }
  /// Node `id`'s segmented view (nullptr when it has none or is unknown yet).
  const DepthView* nodeView(std::size_t id) const {
    return id < nodes_.size() && nodes_[id].view ? &*nodes_[id].view : nullptr;
  }

  /// Forgets the closures an optimiser removed from the graph (their attempts: not accepted,
  /// with the reason). The relocalisation votes that joined two pieces together go together
  /// once fewer than relocalisation_agreeing of them are left (as in DepthSlam): one alone would
  /// be the unchecked join the votes exist to prevent, so this removes the rest from the graph
  /// and returns how many it removed (the graph then needs optimising again). Runs at every
  /// step; call it after the last optimisation, and again after each that follows a removal.
  std::size_t syncWithGraph();

 private:
  struct Node {
    std::optional<DepthView> view;  ///< empty when no scan could be given to the node
    Isometry3 T_robot_camera = Isometry3::Identity();
  };
  /// The scan's mounting and segmented view (no view without a scan, or when it cannot be
  /// converted: then `error` says why).
  Node nodeOf(const mrpt::obs::CObservation3DRangeScan::Ptr& scan, std::string* error);
  /// Node `id`'s view from the linked node decider, when it registered that node's keyframe in
  /// this step with the same segmentation parameters (id 0: the root keyframe, before the root
  /// enters the graph).
  std::optional<Node> keyframeNode(std::size_t id) const;
  void closeLoops(std::size_t k);
  /// The decider's edges i -> i+1 (not breaks) as constraints between camera frames.
  std::vector<PoseConstraint> treeConstraints() const;
  /// Inserts the edge of `c_camera`, the closure of attempts_[attempt]; `group`: the
  /// relocalisation votes inserted together (0: a loop closure).
  void insert(const PoseConstraint& c_camera, std::size_t attempt, std::size_t group);
  std::vector<PoseConstraint> closureConstraints() const;

  /// A closure in the graph.
  struct Closure {
    PoseConstraint constraint;                 ///< between camera frames
    mrpt::poses::CPose3DPDFGaussianInf edge;   ///< as inserted (robot frames), to find it again
    std::size_t attempt = 0;                   ///< its index in attempts_
    std::size_t group = 0;                     ///< relocalisation votes inserted together (0: none)
  };

  PairParams pair_;
  LoopClosureParams loop_;
  std::string sensor_label_;
  std::optional<Node> root_;  ///< the root's node until the root is registered
  std::vector<Node> nodes_;
  /// The nodes' place descriptors (by node id), for loop_search: retrieval or both.
  PlaceIndex places_;
  std::vector<Closure> closures_;  ///< in the graph
  std::size_t vote_groups_ = 0;
  std::vector<LoopClosureAttempt> attempts_;
  RelocalisationVotes votes_{LoopClosureParams{}};  ///< relocalisations waiting for agreement
  const CGaspOdometryNRD* node_decider_ = nullptr;
  std::size_t segmentations_ = 0;
};

}  // namespace gasp::graphslam
