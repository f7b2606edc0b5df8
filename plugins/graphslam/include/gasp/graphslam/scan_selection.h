#pragma once
/// \file scan_selection.h Which depth scans of a rawlog a graph-SLAM run gives the engine
/// (gasp-graphslam --first, --every, --max-scans), and the odometry of the steps it leaves out:
/// composed into the next step that is given, so that the engine's odometry (and MRPT's
/// odometry-based deciders) still follow the whole path.
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/poses/CPose3DPDFGaussian.h>

#include <cstddef>
#include <optional>

namespace gasp::graphslam {

/// The scans used, counted among the deciders' scans in file order (index k = 0, 1, ...).
struct ScanSelection {
  std::size_t first = 0;      ///< the first scan used
  std::size_t every = 1;      ///< then every N-th (N >= 1; a wider baseline between scans)
  std::size_t max_scans = 0;  ///< stop after this many used scans (0 = to the end of the rawlog)

  /// Scan k is used: k >= first and (k - first) is a multiple of `every`.
  bool uses(std::size_t k) const { return k >= first && (k - first) % (every == 0 ? 1 : every) == 0; }
  /// `used` scans are all that is wanted.
  bool done(std::size_t used) const { return max_scans > 0 && used >= max_scans; }
};

/// The motion of the rawlog steps (format #1: an action collection and a sensory frame) a run
/// leaves out, held until the next step that is given to the engine. The engine and MRPT's
/// deciders read a step's first movement estimate (CActionCollection::getFirstMovementEstimation)
/// as its odometry; the given step then carries the left-out steps' motion composed with its own.
class SkippedMotion {
 public:
  /// A left-out step's actions: their first movement estimate (CActionRobotMovement2D or 3D, with
  /// its covariance) is composed after the motion held. Actions without one add nothing.
  void add(const mrpt::obs::CActionCollection::Ptr& actions);
  /// No motion is held.
  bool empty() const { return !motion_.has_value(); }
  /// The actions for a step given to the engine: when motion is held, one
  /// CActionRobotMovement3D with the held motion composed with the step's own first movement
  /// (Gaussian composition, CPose3DPDFGaussian::operator+=) and the timestamp of the step's first
  /// action; the held motion is then cleared. When none is held, `actions` as they are.
  mrpt::obs::CActionCollection::Ptr prepend(const mrpt::obs::CActionCollection::Ptr& actions);

 private:
  std::optional<mrpt::poses::CPose3DPDFGaussian> motion_;
};

}  // namespace gasp::graphslam
