#pragma once
// The median |a - b| of two raw depth images over the pixels with depth in both (raw units): how
// far a map's scan is from a recorded one. Header only; needs MRPT's matrices (gasp::mrpt).
#include <mrpt/math/CMatrixDynamic.h>

#include <opencv2/core.hpp>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <vector>

namespace gasp::test {

/// `b(r, c)` gives b's raw value at (r, c); -1 when no pixel has depth in both.
template <class At>
double medianAbsDifferenceBy(const mrpt::math::CMatrix_u16& a, At b) {
  std::vector<int> d;
  for (int r = 0; r < static_cast<int>(a.rows()); ++r)
    for (int c = 0; c < static_cast<int>(a.cols()); ++c) {
      const int x = a(r, c), y = b(r, c);
      if (x > 0 && y > 0) d.push_back(std::abs(x - y));
    }
  if (d.empty()) return -1.0;
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
  return d[d.size() / 2];
}

inline double medianAbsDifference(const mrpt::math::CMatrix_u16& a, const mrpt::math::CMatrix_u16& b) {
  return medianAbsDifferenceBy(a, [&b](int r, int c) { return static_cast<int>(b(r, c)); });
}

/// b: CV_16UC1 of a's size.
inline double medianAbsDifference(const mrpt::math::CMatrix_u16& a, const cv::Mat& b) {
  return medianAbsDifferenceBy(a, [&b](int r, int c) { return static_cast<int>(b.at<std::uint16_t>(r, c)); });
}

}  // namespace gasp::test
