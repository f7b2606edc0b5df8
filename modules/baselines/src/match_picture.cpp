#include "gasp/baselines/match_picture.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>

#include "gasp/core/error.h"

namespace gasp::baselines {

namespace {

cv::Mat asBgr(const cv::Mat& image) {
  if (image.type() == CV_8UC3) return image;
  if (image.type() == CV_8UC1) {
    cv::Mat out;
    cv::cvtColor(image, out, cv::COLOR_GRAY2BGR);
    return out;
  }
  throw Error("drawKeypointMatches: images must be CV_8UC3 or CV_8UC1");
}

}  // namespace

cv::Mat drawKeypointMatches(const cv::Mat& image_a, const cv::Mat& image_b, const std::vector<cv::Point2f>& keypoints_a,
                            const std::vector<cv::Point2f>& keypoints_b, const std::vector<cv::Point2f>& matched_a,
                            const std::vector<cv::Point2f>& matched_b, const std::vector<unsigned char>& correct,
                            const MatchPictureOptions& options) {
  if (matched_a.size() != matched_b.size()) throw Error("drawKeypointMatches: matched_a and matched_b differ in length");
  if (!correct.empty() && correct.size() != matched_a.size())
    throw Error("drawKeypointMatches: one 'correct' flag per match expected");
  const cv::Mat a = asBgr(image_a), b = asBgr(image_b);
  cv::Mat out(std::max(a.rows, b.rows), a.cols + b.cols, CV_8UC3, cv::Scalar::all(0));
  // Darkened images so that the lines stand out.
  cv::Mat roi_a = out(cv::Rect(0, 0, a.cols, a.rows)), roi_b = out(cv::Rect(a.cols, 0, b.cols, b.rows));
  a.convertTo(roi_a, CV_8UC3, 0.6);
  b.convertTo(roi_b, CV_8UC3, 0.6);
  const cv::Point2f shift(static_cast<float>(a.cols), 0.0f);
  for (const auto& p : keypoints_a) cv::circle(out, p, 1, cv::Scalar(160, 160, 160), cv::FILLED);
  for (const auto& p : keypoints_b) cv::circle(out, p + shift, 1, cv::Scalar(160, 160, 160), cv::FILLED);
  const std::size_t n = matched_a.size();
  const std::size_t lines = std::min<std::size_t>(n, static_cast<std::size_t>(std::max(0, options.max_lines)));
  for (std::size_t k = 0; k < lines; ++k) {
    const std::size_t i = k * n / lines;  // evenly spaced sample
    cv::Scalar colour(255, 255, 255);
    if (!correct.empty()) colour = correct[i] ? cv::Scalar(0, 220, 0) : cv::Scalar(0, 0, 255);
    cv::circle(out, matched_a[i], 3, colour, 1, cv::LINE_AA);
    cv::circle(out, matched_b[i] + shift, 3, colour, 1, cv::LINE_AA);
    cv::line(out, matched_a[i], matched_b[i] + shift, colour, 1, cv::LINE_AA);
  }
  return out;
}

}  // namespace gasp::baselines
