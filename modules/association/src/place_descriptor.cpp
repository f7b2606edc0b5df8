#include "gasp/association/place_descriptor.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "gasp/core/error.h"

namespace gasp {

void validate(const PlaceDescriptorParams& p) {
  if (p.distance_edges_m.empty()) throw Error("place descriptor: distance_edges_m is empty");
  for (std::size_t i = 0; i < p.distance_edges_m.size(); ++i) {
    const double e = p.distance_edges_m[i];
    if (!std::isfinite(e) || e <= 0.0 || (i > 0 && e <= p.distance_edges_m[i - 1]))
      throw Error("place descriptor: distance_edges_m must be finite, positive and ascending");
  }
  if (p.angle_bins < 1 || p.angle_bins > 36) throw Error("place descriptor: angle_bins must be in [1, 36]");
}

PlaceDescriptor describePlace(const std::vector<std::vector<Feature>>& feature_sets, const PlaceDescriptorParams& p) {
  validate(p);
  const std::size_t distance_bins = p.distance_edges_m.size() + 1, a = static_cast<std::size_t>(p.angle_bins);
  std::vector<double> counts(distance_bins * a * a * a, 0.0);
  const auto angleBin = [&](double theta) {
    const auto b = static_cast<std::size_t>(std::floor(theta / M_PI * static_cast<double>(a)));
    return std::min(b, a - 1);  // theta = pi falls in the last bin
  };
  PlaceDescriptor out;
  for (const auto& set : feature_sets)
    for (const Feature& q : set) {
      if (!std::all_of(q.begin() + 3, q.end(), [](double v) { return std::isfinite(v); })) continue;
      const std::size_t d = static_cast<std::size_t>(
          std::upper_bound(p.distance_edges_m.begin(), p.distance_edges_m.end(), q[3]) - p.distance_edges_m.begin());
      counts[((d * a + angleBin(q[4])) * a + angleBin(q[5])) * a + angleBin(q[6])] += 1.0;
      ++out.features;
    }
  if (out.features == 0) return out;
  out.sqrt_frequencies.resize(counts.size());
  for (std::size_t i = 0; i < counts.size(); ++i)
    out.sqrt_frequencies[i] = static_cast<float>(std::sqrt(counts[i] / static_cast<double>(out.features)));
  return out;
}

double placeDistance(const PlaceDescriptor& a, const PlaceDescriptor& b) {
  if (a.sqrt_frequencies.empty() || b.sqrt_frequencies.empty()) return 1.0;
  if (a.sqrt_frequencies.size() != b.sqrt_frequencies.size())
    throw Error("place descriptors of different sizes (" + std::to_string(a.sqrt_frequencies.size()) + " and " +
                std::to_string(b.sqrt_frequencies.size()) + "): made with other parameters");
  double bc = 0.0;  // the Bhattacharyya coefficient; |a - b|^2 = 2 - 2 bc for unit vectors
  for (std::size_t i = 0; i < a.sqrt_frequencies.size(); ++i)
    bc += static_cast<double>(a.sqrt_frequencies[i]) * static_cast<double>(b.sqrt_frequencies[i]);
  return std::sqrt(std::max(0.0, 1.0 - bc));
}

const PlaceDescriptor* PlaceIndex::find(std::size_t id) const {
  const auto it = std::find(ids_.begin(), ids_.end(), id);
  return it == ids_.end() ? nullptr : &descriptors_[static_cast<std::size_t>(it - ids_.begin())];
}

bool PlaceIndex::add(std::size_t id, PlaceDescriptor descriptor) {
  if (descriptor.sqrt_frequencies.empty()) return false;
  const auto it = std::find(ids_.begin(), ids_.end(), id);
  if (it != ids_.end()) {
    descriptors_[static_cast<std::size_t>(it - ids_.begin())] = std::move(descriptor);
    return true;
  }
  ids_.push_back(id);
  descriptors_.push_back(std::move(descriptor));
  return true;
}

std::vector<std::pair<std::size_t, double>> PlaceIndex::nearest(std::vector<std::pair<std::size_t, double>> all,
                                                                std::size_t k) {
  const auto closer = [](const auto& x, const auto& y) { return x.second < y.second || (x.second == y.second && x.first < y.first); };
  if (all.size() > k) {
    std::partial_sort(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(k), all.end(), closer);
    all.resize(k);
  } else {
    std::sort(all.begin(), all.end(), closer);
  }
  return all;
}

}  // namespace gasp
