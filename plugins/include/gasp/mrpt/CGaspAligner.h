#pragma once
/// \file CGaspAligner.h GASP as an mrpt::slam::CMetricMapsAlignmentAlgorithm: the pose of map m2
/// relative to map m1 (both gasp::CSuperpixelMap), or of one observation relative to another,
/// from patch associations, RANSAC and the point-to-plane refinement (pair_registration.h). No
/// initial guess is needed; the one passed is ignored.
///
/// Maps of several views: every view pair (i of m1, j of m2) is registered and the claimed
/// estimate with the most inliers is kept. The returned CPose3DPDFGaussian has the covariance
/// J I^-1 J^T of that pair's edge information I (PairResult::edge_information, pose_covariance.h):
/// the refinement's first-order uncertainty plus the model error (options.params.certify.model_error,
/// keys model_error_t_m / model_error_r_deg; model_error.h), since the refinement's alone is
/// 100-1000 times too certain on real data (docs/pipeline.md).
/// When no pose is claimed (no associations, no consensus, degenerate geometry, failed
/// visibility check, information not positive definite) Align3DPDF / AlignPDF return nullptr and
/// the result info says why.
///
/// Also a mrpt::rtti::CObject, so mrpt::rtti::classFactory("gasp::CGaspAligner") creates it.
#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/obs/CObservation.h>
#include <mrpt/poses/CPose3DPDFGaussian.h>
#include <mrpt/poses/CPosePDFGaussian.h>
#include <mrpt/rtti/CObject.h>
#include <mrpt/slam/CMetricMapsAlignmentAlgorithm.h>

#include <string>
#include <utility>
#include <vector>

#include "gasp/mrpt/pose_covariance.h"
#include "gasp/pipeline/pair_registration.h"
#include "gasp/pipeline/range_view.h"

namespace gasp {

/// What CGaspAligner reports besides the pose (executionTime, in the base, is in seconds).
struct TGaspAlignmentResult : public mrpt::slam::TMetricMapAlignmentResult {
  bool success = false;     ///< a pose is claimed (the returned PDF is not null)
  bool degenerate = false;  ///< some direction is unobservable
  std::string reason;       ///< why no pose is claimed
  int view_m1 = -1, view_m2 = -1;  ///< the view pair the estimate rests on (or the best failed one)
  std::vector<std::pair<int, int>> associations;  ///< (patch of view_m1, patch of view_m2); empty when finer_scale
  /// The pose came from the finer-scale retry (PairParams::retry_area_factor): its patches are not
  /// the maps' own, so no associations are listed.
  bool finer_scale = false;
  int inliers = 0;
  /// Information of the pose of m2 in m1 over the left perturbation in m1's frame,
  /// xi = [t; omega] ([m], [rad]): the pair's edge information (the refinement's with the model
  /// error, PairResult::edge_information); zero when no pose is claimed.
  Matrix6 information = Matrix6::Zero();
  int view_pairs = 0;   ///< view pairs registered
  double time_ms = 0.0;
};

class CGaspAligner : public mrpt::slam::CMetricMapsAlignmentAlgorithm, public mrpt::rtti::CObject {
  DEFINE_MRPT_OBJECT(CGaspAligner, gasp)
 public:
  /// The matching keys of params_io.h (ini section of your choice).
  struct TOptions : public mrpt::config::CLoadableOptions {
    PairParams params;  ///< maps of depth images' views
    /// Maps of LiDAR sweeps' views: lidarPairParams(lidar, params) (the same section, the params
    /// file's lidar keys). Two maps are aligned when all their views are of one kind.
    LidarParams lidar;
    void loadFromConfigFile(const mrpt::config::CConfigFileBase& source, const std::string& section) override;
    void saveToConfigFile(mrpt::config::CConfigFileBase& target, const std::string& section) const override;
  };
  TOptions options;

  CGaspAligner();

  /// Pose of m2 relative to m1: each a CSuperpixelMap, or a CMultiMetricMap holding exactly one
  /// (CSuperpixelMap::findIn); other maps throw. nullptr = no estimate, with the reason in
  /// outInfo (a TGaspAlignmentResult) -- unlike CICP, which always returns a pose and rates it
  /// with `goodness`; GASP does not hand out a pose it does not claim.
  mrpt::poses::CPose3DPDF::Ptr Align3DPDF(
      const mrpt::maps::CMetricMap* m1, const mrpt::maps::CMetricMap* m2,
      const mrpt::poses::CPose3DPDFGaussian& initialEstimationPDF,
      mrpt::optional_ref<mrpt::slam::TMetricMapAlignmentResult> outInfo = std::nullopt) override;
  /// The same projected on the plane: (x, y, yaw) and their covariance block. nullptr = no estimate.
  mrpt::poses::CPosePDF::Ptr AlignPDF(
      const mrpt::maps::CMetricMap* m1, const mrpt::maps::CMetricMap* m2,
      const mrpt::poses::CPosePDFGaussian& initialEstimationPDF,
      mrpt::optional_ref<mrpt::slam::TMetricMapAlignmentResult> outInfo = std::nullopt) override;

  /// Pose of observation b's robot frame in observation a's robot frame (sensorPose honoured);
  /// both CObservation3DRangeScan (segmented with options.params.segment), or both LiDAR sweeps
  /// (CObservationRotatingScan, CObservationVelodyneScan, CObservationPointCloud: options.lidar);
  /// others throw.
  /// nullptr = no estimate.
  mrpt::poses::CPose3DPDFGaussian::Ptr alignObservations(
      const mrpt::obs::CObservation& a, const mrpt::obs::CObservation& b,
      mrpt::optional_ref<mrpt::slam::TMetricMapAlignmentResult> outInfo = std::nullopt);
};

}  // namespace gasp
