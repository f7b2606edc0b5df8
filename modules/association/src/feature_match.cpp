#include "gasp/association/feature_match.h"

#include <string>

#include "gasp/core/error.h"

namespace gasp {

void validate(const MatchParams& params) {
  if (!(params.r_dev_m >= 0.0) || !std::isfinite(params.r_dev_m) ||
      !(params.theta_dev_rad >= 0.0) || !std::isfinite(params.theta_dev_rad)) {
    throw Error("MatchParams: r_dev_m and theta_dev_rad must be finite and >= 0, got " +
                std::to_string(params.r_dev_m) + " m and " + std::to_string(params.theta_dev_rad) + " rad");
  }
}

}  // namespace gasp
