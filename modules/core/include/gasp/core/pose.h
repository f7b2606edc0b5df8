#pragma once
/// \file pose.h Rigid poses as Eigen isometries, named by frames.
///
/// Convention: T_a_b maps coordinates in frame b to frame a (p_a = T_a_b * p_b), so
/// T_world_camera is the camera's pose in the world and T_target_source takes source-view points
/// into the target view. Camera frames are optical (x right, y down, z forward), as in TUM.
#include <Eigen/Geometry>

#include <vector>

namespace gasp {

using Isometry3 = Eigen::Isometry3d;

/// Pose from a TUM line's numbers (translation, Hamilton quaternion with w last). The quaternion
/// is normalised; a zero or non-finite quaternion throws gasp::Error.
Isometry3 poseFromTranslationQuaternion(double tx, double ty, double tz, double qx, double qy,
                                        double qz, double qw);

/// T_a_b = T_world_a^-1 * T_world_b.
inline Isometry3 relativePose(const Isometry3& T_world_a, const Isometry3& T_world_b) {
  return T_world_a.inverse() * T_world_b;
}

/// Rotation angle [rad] of a pose's rotation, acos((trace(R) - 1) / 2) clamped to [0, pi].
double rotationAngle(const Isometry3& T);

/// Translation length [m].
inline double translationNorm(const Isometry3& T) { return T.translation().norm(); }

/// A point set's first two moments: what the RMS displacement between two poses needs.
struct PointSpread {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  ///< (1/n) sum (p - mean)(p - mean)^T
};

/// The moments of `points` (zero for none).
PointSpread pointSpread(const std::vector<Eigen::Vector3d>& points);

/// RMS over the points of |T_a p - T_b p| [m], exactly from their moments:
/// |D mean + dt|^2 + trace(D^T D covariance), D = R_a - R_b, dt = t_a - t_b.
double rmsDisplacement(const Isometry3& T_a, const Isometry3& T_b, const PointSpread& points);

}  // namespace gasp
