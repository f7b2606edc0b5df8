#include "gasp/pipeline/model_error.h"

#include <Eigen/Cholesky>

#include <cmath>

#include "gasp/core/error.h"

namespace gasp {

void validate(const ModelError& e) {
  // Above 100 m or 180 deg a standard deviation says nothing more, and its square would swamp
  // the information in double precision.
  if (!(e.sigma_t_m >= 0.0 && e.sigma_t_m <= 100.0)) throw Error("ModelError: sigma_t_m must be from 0 to 100 m");
  if (!(e.sigma_r_deg >= 0.0 && e.sigma_r_deg <= 180.0))
    throw Error("ModelError: sigma_r_deg must be from 0 to 180 deg");
}

Eigen::Matrix<double, 6, 6> modelErrorCovariance(const ModelError& e) {
  validate(e);
  const double sr = e.sigma_r_deg * M_PI / 180.0;
  Eigen::Matrix<double, 6, 1> d;
  d << e.sigma_t_m * e.sigma_t_m, e.sigma_t_m * e.sigma_t_m, e.sigma_t_m * e.sigma_t_m, sr * sr, sr * sr, sr * sr;
  return d.asDiagonal();
}

Eigen::Matrix<double, 6, 6> informationWithModelError(const Eigen::Matrix<double, 6, 6>& information,
                                                      const ModelError& e) {
  using Matrix6 = Eigen::Matrix<double, 6, 6>;
  validate(e);
  if (!information.allFinite()) throw Error("informationWithModelError: the information is not finite");
  const Matrix6 I = 0.5 * (information + information.transpose());
  const Eigen::LLT<Matrix6> llt(I);
  if (llt.info() != Eigen::Success) throw Error("informationWithModelError: the information is not positive definite");
  if (e.sigma_t_m == 0.0 && e.sigma_r_deg == 0.0) return information;
  Matrix6 C = llt.solve(Matrix6::Identity()) + modelErrorCovariance(e);
  C = 0.5 * (C + C.transpose());
  const Eigen::LLT<Matrix6> llt_c(C);
  if (llt_c.info() != Eigen::Success) throw Error("informationWithModelError: the covariance is not positive definite");
  Matrix6 I_edge = llt_c.solve(Matrix6::Identity());
  return 0.5 * (I_edge + I_edge.transpose());
}

}  // namespace gasp
