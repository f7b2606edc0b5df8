#pragma once
/// \file place_descriptor.h A view's place descriptor for retrieval without appearance: the
/// distribution of its invariant features (invariant_feature.h) over every patch's neighbourhood
/// (feature_sets.h), as GASP's association computes them.
///
/// Each feature q(mu, alpha) gives one count in a 4-D histogram over its rigid-motion invariant
/// part: the centroid distance |r| (q[3]) and the three angles theta(n_mu, n_alpha),
/// theta(r, n_mu), theta(r, n_alpha) (q[4..6]). The first three components are left out: their
/// signs follow the local basis, so they add no invariance but split counts. Like the features,
/// the descriptor does not change with the camera's pose (a 180-degree roll included); it changes
/// with what the view sees. Descriptors are compared by the Hellinger distance: the histogram is
/// stored as the square roots of its frequencies, a unit vector, and two places are
/// d = |a - b| / sqrt(2) apart, in [0, 1] (0: the same distribution).
///
/// PlaceIndex keeps descriptors by id and returns the nearest k to a query, by exhaustive search:
/// a descriptor has a few hundred numbers, so a query over thousands of keyframes is a
/// fraction of a millisecond (bench_place_retrieval).
#include <cstddef>
#include <utility>
#include <vector>

#include "gasp/association/invariant_feature.h"

namespace gasp {

struct PlaceDescriptorParams {
  /// Upper edges of the distance bins [m], ascending; a last bin holds the longer distances.
  std::vector<double> distance_edges_m = {0.1, 0.2, 0.4, 0.8};
  int angle_bins = 6;  ///< bins of each angle over [0, pi]
};

/// Throws gasp::Error naming the first invalid parameter.
void validate(const PlaceDescriptorParams& params);

struct PlaceDescriptor {
  std::vector<float> sqrt_frequencies;  ///< unit vector (empty: no feature, nothing to compare)
  std::size_t features = 0;             ///< features counted
};

/// The descriptor of a view from its feature sets (computeFeatureSets()). Non-finite features are
/// skipped. Validates params.
PlaceDescriptor describePlace(const std::vector<std::vector<Feature>>& feature_sets,
                              const PlaceDescriptorParams& params = {});

/// Hellinger distance in [0, 1]; 1 when either is empty. Throws gasp::Error for descriptors of
/// different sizes (other parameters).
double placeDistance(const PlaceDescriptor& a, const PlaceDescriptor& b);

/// Descriptors by id, searched exhaustively.
class PlaceIndex {
 public:
  /// Adds (or replaces) the descriptor of `id`; an empty descriptor is not added (false).
  bool add(std::size_t id, PlaceDescriptor descriptor);
  std::size_t size() const { return ids_.size(); }
  /// The descriptor of `id`, or null.
  const PlaceDescriptor* find(std::size_t id) const;
  /// The `k` nearest to `query` (id, distance), nearest first, ties by id; `exclude(id)` true
  /// leaves an id out (e.g. the query's own recent keyframes). Empty for an empty query.
  template <class Exclude>
  std::vector<std::pair<std::size_t, double>> query(const PlaceDescriptor& query, std::size_t k,
                                                    Exclude&& exclude) const {
    std::vector<std::pair<std::size_t, double>> all;
    if (query.sqrt_frequencies.empty()) return all;
    all.reserve(ids_.size());
    for (std::size_t i = 0; i < ids_.size(); ++i)
      if (!exclude(ids_[i])) all.emplace_back(ids_[i], placeDistance(query, descriptors_[i]));
    return nearest(std::move(all), k);
  }
  std::vector<std::pair<std::size_t, double>> query(const PlaceDescriptor& q, std::size_t k) const {
    return query(q, k, [](std::size_t) { return false; });
  }

 private:
  static std::vector<std::pair<std::size_t, double>> nearest(std::vector<std::pair<std::size_t, double>> all,
                                                             std::size_t k);
  std::vector<std::size_t> ids_;
  std::vector<PlaceDescriptor> descriptors_;
};

}  // namespace gasp
