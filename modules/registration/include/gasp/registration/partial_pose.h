#pragma once
/// \file partial_pose.h A pose claimed only in the directions its terms observe.
///
/// When the information of an estimate leaves k directions unobservable (degeneracy.h: a floor
/// leaves the two translations along it and the rotation about its normal, a corridor its axis),
/// the estimate says nothing along them: a pose graph must get zero information there, an
/// odometry must keep its prediction there, and the estimate's error can be judged only in the
/// observed directions. All three use the oblique projector onto the observed directions,
///   Pi = B S (I - U U^T) (B S)^-1,
/// with U the orthonormal basis of the unobservable directions in the conditioned coordinates
/// (RegistrationResult::unobservable_directions) and B S the conditioning of degeneracy.h
/// (rotations about the scene centre, as arc lengths at the scene radius).
#include <Eigen/Core>

#include "gasp/core/pose.h"
#include "gasp/registration/registration_result.h"

namespace gasp {

/// A partial pose needs at least the three directions one plane fixes: with more than this many
/// unobservable directions the terms do not even pin a plane, and there is no estimate.
inline constexpr int kMaxFreeDirections = 3;

/// Free directions closer than this are one (unitedDirections()) [deg].
inline constexpr double kSameDirectionDeg = 30.0;

/// Pi for r's unobservable directions (the identity when there are none). Maps a left
/// perturbation [t r] of T_target_source to its observed part.
Matrix6d observedProjector(const RegistrationResult& r);

/// Pi^T I Pi: r.information (or `information`, in the same coordinates) with exactly r's
/// unobservable directions given zero information.
Matrix6d observedInformation(const RegistrationResult& r, const Matrix6d& information);

/// The information of r's observed directions after adding a covariance (in the same
/// coordinates as the information, e.g. a model error): with Q an orthonormal basis of the
/// observed directions and U of the free ones (conditioned), the observed directions' marginal
/// M = Q^T I_c Q - Q^T I_c U (U^T I_c U)^+ U^T I_c Q (the free ones are unknown: what the
/// information says about them is taken out), then (M^-1 + Q^T C_c Q)^-1 on them, and the
/// unobservable directions get zero. Throws gasp::Error when the information is not positive
/// definite on the observed directions or not finite.
Matrix6d observedInformationWithCovariance(const RegistrationResult& r, const Matrix6d& information,
                                           const Matrix6d& added_covariance);

/// The basis U spanning both r's unobservable directions and `more` (raw left perturbations
/// [t r] of T_target_source, one per column), orthonormal in r's conditioned coordinates. Two
/// analyses of the same views find the same free direction a few degrees apart (noise, other
/// centres of conditioning): directions closer than kSameDirectionDeg count once (the
/// eigenvectors of the sum of their projectors above 1 - cos(kSameDirectionDeg)).
Eigen::Matrix<double, 6, Eigen::Dynamic> unitedDirections(const RegistrationResult& r,
                                                          const Eigen::Matrix<double, 6, Eigen::Dynamic>& more);

/// The raw left perturbations [t r] of T_target_source along r's unobservable directions, one
/// unit (conditioned) column each.
Eigen::Matrix<double, 6, Eigen::Dynamic> unobservableTwists(const RegistrationResult& r);

/// The error of r.T_target_source against the truth in the observed directions only: the left
/// perturbation from the truth, conditioned, with its unobservable components removed --
/// translation of the scene centre [m] and rotation [deg].
struct ObservedError {
  double translation_m = 0.0;
  double rotation_deg = 0.0;
};
ObservedError observedError(const RegistrationResult& r, const Isometry3& T_true);

/// The pose that agrees with r.T_target_source in the observed directions and with `predicted`
/// in the unobservable ones: r's pose moved along its unobservable directions only,
/// T <- Exp((I - Pi) xi) T with xi the left perturbation from T to `predicted`, three times from
/// r.T_target_source (each move is first order in the free difference; repeated, it converges).
/// Where the unobservable directions are symmetries of the scene (sliding along a floor), this
/// leaves the observed directions exactly as r found them.
Isometry3 withPrediction(const RegistrationResult& r, const Isometry3& predicted);

}  // namespace gasp
