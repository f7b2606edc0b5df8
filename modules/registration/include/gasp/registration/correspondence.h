#pragma once
/// \file correspondence.h The input of registration: associated surface patches of a source view
/// and a target view, and optional dense point-to-plane terms.
///
/// T_target_source maps source-frame points into the target frame: p_target ~ T_target_source *
/// p_source (see gasp/core/pose.h). Camera frames are optical (x right, y down, z forward).
#include <Eigen/Core>

#include <string>
#include <vector>

namespace gasp {

/// One associated patch pair.
struct PatchCorrespondence {
  Eigen::Vector3d p_source = Eigen::Vector3d::Zero();  ///< patch centroid [m], source camera frame
  Eigen::Vector3d n_source = Eigen::Vector3d::UnitZ(); ///< unit patch normal, source camera frame
  Eigen::Vector3d p_target = Eigen::Vector3d::Zero();  ///< the same in the target camera frame [m]
  Eigen::Vector3d n_target = Eigen::Vector3d::UnitZ(); ///< unit normal, target camera frame
  /// Confidence >= 0 (e.g. 1 - normalised edit distance); multiplies the term's robust cost.
  double weight = 1.0;
};

/// A dense term: a source point against a target plane (e.g. a patch's pixels against the
/// associated patch's plane).
struct PointToPlane {
  Eigen::Vector3d p_source = Eigen::Vector3d::Zero();  ///< point [m], source camera frame
  Eigen::Vector3d q_target = Eigen::Vector3d::Zero();  ///< a point of the plane [m], target frame
  Eigen::Vector3d n_target = Eigen::Vector3d::UnitZ(); ///< unit plane normal, target frame
  double weight = 1.0;                                  ///< >= 0, multiplies the robust cost
};

/// Empty when every term is usable; otherwise why not, naming the first bad index: a non-finite
/// component, a normal whose length is not 1 within 1e-3 (normals are used as given), or a
/// negative weight.
std::string invalidInput(const std::vector<PatchCorrespondence>& correspondences);
std::string invalidInput(const std::vector<PointToPlane>& terms);

}  // namespace gasp
