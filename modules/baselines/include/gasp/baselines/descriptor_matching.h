#pragma once
/// \file descriptor_matching.h Nearest neighbours in descriptor space (Euclidean), the same rule for
/// every baseline: keypoint a of view A is matched to its nearest descriptor b in view B when
///   ratio test   d(a, b) <= ratio * d(a, b2)   (b2 the second nearest; Lowe 2004), and
///   mutual check a is also b's nearest neighbour in A (when `mutual`).
/// Neighbours come from FLANN randomised KD-trees (cv::flann, `trees` trees, `checks` leaves
/// visited; approximate; FLANN draws its random split dimensions from std::rand, so std::srand(1)
/// is called before each index is built and runs repeat) or, for at most exact_below descriptors
/// in B (and A), from an exhaustive search (cv::BFMatcher).
#include <opencv2/core.hpp>

#include <vector>

namespace gasp::baselines {

struct MatchParams {
  double ratio = 0.8;        ///< Lowe's ratio test threshold, in (0, 1]
  bool mutual = true;        ///< keep a match only if it is the nearest neighbour both ways
  int trees = 4;             ///< FLANN KD-trees
  int checks = 32;           ///< FLANN leaves visited per query
  int exact_below = 2000;    ///< exhaustive search when both views have at most this many descriptors
};

/// Throws gasp::Error naming the first invalid parameter.
void validate(const MatchParams& params);

struct DescriptorMatch {
  int a = -1, b = -1;     ///< row in A's / B's descriptors
  float distance = 0.0f;  ///< Euclidean descriptor distance
};

/// Matches in ascending order of a. Throws gasp::Error when the descriptor types or widths differ
/// or are not CV_32F. Fewer than 2 descriptors in B give no matches (no ratio test possible).
std::vector<DescriptorMatch> matchDescriptors(const cv::Mat& descriptors_a, const cv::Mat& descriptors_b,
                                              const MatchParams& params = {});

}  // namespace gasp::baselines
