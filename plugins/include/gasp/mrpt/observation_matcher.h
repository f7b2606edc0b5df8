#pragma once
/// \file observation_matcher.h GASP's observation matcher interface on mrpt::rtti (MRPT 2.5 has
/// no registry of its own): a matcher is created by class name with its parameters from YAML, as
/// mp2p_icp creates its matchers, and matches two observations into a relative-pose constraint.
#include <mrpt/containers/yaml.h>
#include <mrpt/obs/CObservation.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/rtti/CObject.h>

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace gasp {

/// What a matcher returns: the pose of observation b's robot frame in observation a's robot frame
/// (the edge a -> b of a pose graph), or no estimate with the reason.
struct MatchConstraint {
  bool success = false;            ///< a full pose is claimed
  bool degenerate = false;         ///< some direction unobservable: no full pose is claimed
  /// A partial pose is claimed (success false; docs/pipeline.md "Step 5. Certify"): T_a_b holds in
  /// the observed directions only, `information` is zero along each column of free_directions.
  /// Not a constraint for a graph that treats edges as full poses.
  bool partial = false;
  /// Partial only: the free directions as unit left perturbations [t; omega] of T_a_b in a's
  /// robot frame (as `information`), one per column.
  Eigen::Matrix<double, 6, Eigen::Dynamic> free_directions;
  mrpt::poses::CPose3D T_a_b;      ///< robot frame of b in robot frame of a (sensorPose honoured)
  /// 6x6 information of T_a_b over the left perturbation T_a_b <- Exp(xi) T_a_b, xi = [t; omega]
  /// in a's robot frame ([m], [rad]): the refinement's (from its Jacobians, docs/registration.md)
  /// with the model error added (PairResult::edge_information, model_error.h).
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();
  std::vector<std::pair<int, int>> associations;  ///< (patch of a, patch of b); empty when finer_scale or deskewed
  /// The pose came from the finer-scale retry (PairParams::retry_area_factor): its patches are not
  /// those of the default decomposition, so no associations are listed.
  bool finer_scale = false;
  /// Two sweeps that moved while taken, deskewed with their own motion and registered again
  /// (stage 8, docs/lidar.md "Motion within a sweep"): the associations are between the deskewed
  /// sweeps' patches, so none are listed.
  bool deskewed = false;
  int inliers = 0;
  double time_ms = 0.0;
  std::string reason;  ///< why there is no estimate; for a partial pose, which directions are free
};

/// Base class of observation matchers, created by name through mrpt::rtti.
class ObservationMatcher : public mrpt::rtti::CObject {
  DEFINE_VIRTUAL_MRPT_OBJECT(ObservationMatcher)
 public:
  /// Reads the parameters; unknown keys and invalid values throw std::exception with a message
  /// naming them.
  virtual void initialize(const mrpt::containers::yaml& params) = 0;
  /// Matches b against a. Observations of an unsupported type throw; data problems (no depth,
  /// no overlap, degenerate scene) give success = false with a reason. GASP needs no initial
  /// guess; ObservationMatcher_GASP ignores it (other matchers may use it).
  virtual MatchConstraint match(const mrpt::obs::CObservation& a, const mrpt::obs::CObservation& b,
                                const std::optional<mrpt::poses::CPose3D>& initial_guess = std::nullopt) const = 0;
};

/// Creates the matcher registered under `class_name` (e.g. "gasp::ObservationMatcher_GASP") and
/// initialises it with `params`. Throws std::exception for an unknown class name or one that is
/// not an ObservationMatcher.
std::shared_ptr<ObservationMatcher> createObservationMatcher(const std::string& class_name,
                                                             const mrpt::containers::yaml& params = {});

}  // namespace gasp
