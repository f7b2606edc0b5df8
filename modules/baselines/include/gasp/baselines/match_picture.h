#pragma once
/// \file match_picture.h A picture of keypoint matches between two views, to set beside GASP's
/// association picture (gasp/association/association_picture.h): the two images side by side,
/// every keypoint a small grey dot, lines joining an evenly spaced sample of the matched keypoints,
/// green when the match is known correct, red when known wrong, white when unknown.
#include <opencv2/core.hpp>

#include <vector>

namespace gasp::baselines {

struct MatchPictureOptions {
  int max_lines = 60;  ///< lines drawn for at most this many matches (evenly sampled)
};

/// BGR picture of width wa + wb and height max(ha, hb). image_a/b: CV_8UC3 (or CV_8UC1, shown in
/// grey). keypoints_a/b: all keypoints; matched_a/b: the matched pairs (same length); `correct`:
/// empty or one flag per match (1 correct, 0 wrong). Throws gasp::Error for mismatched lengths.
cv::Mat drawKeypointMatches(const cv::Mat& image_a, const cv::Mat& image_b, const std::vector<cv::Point2f>& keypoints_a,
                            const std::vector<cv::Point2f>& keypoints_b, const std::vector<cv::Point2f>& matched_a,
                            const std::vector<cv::Point2f>& matched_b, const std::vector<unsigned char>& correct = {},
                            const MatchPictureOptions& options = {});

}  // namespace gasp::baselines
