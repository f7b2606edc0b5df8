#pragma once
// Internal: the pose problem behind refinement.h -- point-to-plane terms on T_target_source,
// solved by Ceres (an Eigen quaternion on EigenQuaternionManifold and a translation, one residual
// block per term) or on the 6 x 6 normal equations over the left perturbation xi = [rho; omega].
#include <ceres/ceres.h>

#include <cstddef>
#include <vector>

#include "gasp/registration/correspondence.h"
#include "gasp/registration/refinement.h"

namespace gasp::detail {

/// What a solve did, whichever solver ran.
struct PoseSolve {
  bool usable = true;   ///< the pose may be used (Ceres: Summary::IsSolutionUsable)
  int iterations = 0;   ///< successful and unsuccessful steps
  std::string message;  ///< why not usable
};

class PoseProblem {
 public:
  PoseProblem(const Isometry3& T_init, const RefinementParams& params);

  /// Room for this many terms, so that adding them allocates once: thousands of dense terms
  /// otherwise reallocate and copy (and touch fresh pages) at each doubling, in every round.
  void reserve(std::size_t terms) { terms_.reserve(terms); }
  void addPatch(const PatchCorrespondence& c);  ///< forward term, and backward if bidirectional
  void addDense(const PointToPlane& term);
  int numResiduals() const { return static_cast<int>(terms_.size()); }

  PoseSolve solve();  ///< by params.solver, from the current pose
  const Isometry3& pose() const { return T_; }
  void setPose(const Isometry3& T);  ///< moves the parameters (no solve)
  /// Residuals [m] at the current pose, without weights or robust loss.
  std::vector<double> residuals() const;
  /// J^T J / sigma^2 over xi = [rho; omega] (refinement.h), robustified and weighted.
  Matrix6d information() const;
  /// Weighted centroid and RMS radius [m] of the terms' points in the target frame.
  void sceneExtent(Eigen::Vector3d& centre, double& radius_m) const;

 private:
  /// forward:  r = n . (R a + t - b)       (a source point, b a target point on the plane n)
  /// backward: r = n . (R^T (b - t) - a)   (b a target point, mapped back, against the source plane (a, n))
  struct Term {
    Eigen::Vector3d a, b, n;
    double weight;
    bool backward;
  };
  /// One robustified, weighted term at T: its residual, Jacobian over xi, w rho and w rho'.
  struct Linearised {
    double r, rho, rho1;
    Vector6d J;
  };
  Linearised linearise(const Term& term, const Isometry3& T) const;
  /// The normal equations at T: cost = 1/2 sum w rho, H = sum w rho' J J^T, g = sum w rho' r J.
  struct NormalEquations {
    double cost = 0.0;
    Matrix6d H = Matrix6d::Zero();
    Vector6d g = Vector6d::Zero();
  };
  NormalEquations equationsAt(const Isometry3& T) const;
  void add(const Term& term);
  PoseSolve solveByCeres();
  PoseSolve solveByNormalEquations();

  RefinementParams params_;
  Isometry3 T_;
  std::vector<Term> terms_;
};

}  // namespace gasp::detail
