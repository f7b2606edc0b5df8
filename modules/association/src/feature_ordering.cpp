#include "gasp/association/feature_ordering.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "gasp/core/error.h"

namespace gasp {
namespace {

std::int64_t binOf(double scaled) { return detail::floorKey(scaled); }

}  // namespace

void validate(const OrderingParams& params) {
  if (!(params.e_r_m > 0.0) || !std::isfinite(params.e_r_m)) {
    throw Error("OrderingParams::e_r_m must be finite and > 0 m, got " + std::to_string(params.e_r_m));
  }
  if (!(params.e_theta_rad > 0.0) || !std::isfinite(params.e_theta_rad)) {
    throw Error("OrderingParams::e_theta_rad must be finite and > 0 rad, got " +
                std::to_string(params.e_theta_rad));
  }
}

FeatureKey quantise(const Feature& q, const OrderingParams& params) {
  // Division (not multiplication by 1/tol) so that keys are floor(q / tol) as documented.
  FeatureKey key{};
  for (std::size_t i = 0; i < q.size(); ++i) {
    const double tol = i < kFeatureDistanceComponents ? params.e_r_m : params.e_theta_rad;
    key[i] = binOf(q[i] / tol);
  }
  return key;
}

void sortFeatures(std::vector<Feature>& features, const OrderingParams& params) {
  validate(params);
  struct Item {
    FeatureKey key;
    Feature value;
  };
  std::vector<Item> items;
  items.reserve(features.size());
  for (const auto& q : features) items.push_back(Item{quantise(q, params), q});
  // (key, value) lexicographic: a refinement of TolerantFeatureLess that is a total order on
  // distinct finite features, hence a deterministic result whatever the input order.
  std::sort(items.begin(), items.end(), [](const Item& a, const Item& b) {
    if (a.key != b.key) return a.key < b.key;
    return a.value < b.value;
  });
  for (std::size_t i = 0; i < items.size(); ++i) features[i] = items[i].value;
}

}  // namespace gasp
