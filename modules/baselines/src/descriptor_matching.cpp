#include "gasp/baselines/descriptor_matching.h"

#include <opencv2/features2d.hpp>
#include <opencv2/flann.hpp>

#include <cmath>
#include <cstdlib>

#include "gasp/core/error.h"

namespace gasp::baselines {

namespace {

/// k nearest neighbours (Euclidean) of every row of `query` among the rows of `train`:
/// indices and distances, k columns each (-1 / inf where train has fewer rows).
void knn(const cv::Mat& query, const cv::Mat& train, int k, bool exact, const MatchParams& params, cv::Mat& indices,
         cv::Mat& distances) {
  indices.create(query.rows, k, CV_32S);
  distances.create(query.rows, k, CV_32F);
  indices.setTo(-1);
  distances.setTo(std::numeric_limits<float>::infinity());
  if (query.empty() || train.empty()) return;
  if (exact) {
    cv::BFMatcher bf(cv::NORM_L2);
    std::vector<std::vector<cv::DMatch>> m;
    bf.knnMatch(query, train, m, k);
    for (int q = 0; q < query.rows; ++q)
      for (std::size_t j = 0; j < m[static_cast<std::size_t>(q)].size(); ++j) {
        indices.at<int>(q, static_cast<int>(j)) = m[static_cast<std::size_t>(q)][j].trainIdx;
        distances.at<float>(q, static_cast<int>(j)) = m[static_cast<std::size_t>(q)][j].distance;
      }
    return;
  }
  // FLANN draws its random split dimensions from std::rand: seed it so that runs repeat.
  std::srand(1);
  cv::flann::Index index(train, cv::flann::KDTreeIndexParams(params.trees), cvflann::FLANN_DIST_L2);
  cv::Mat idx, d2;
  index.knnSearch(query, idx, d2, k, cv::flann::SearchParams(params.checks));
  for (int q = 0; q < query.rows; ++q)
    for (int j = 0; j < k; ++j) {
      const int i = idx.at<int>(q, j);
      if (i < 0 || i >= train.rows) continue;
      indices.at<int>(q, j) = i;
      distances.at<float>(q, j) = std::sqrt(std::max(0.0f, d2.at<float>(q, j)));  // FLANN L2 is squared
    }
}

}  // namespace

void validate(const MatchParams& p) {
  if (!(p.ratio > 0 && p.ratio <= 1)) throw Error("MatchParams: ratio must be in (0, 1]");
  if (p.trees < 1) throw Error("MatchParams: trees must be >= 1");
  if (p.checks < 1) throw Error("MatchParams: checks must be >= 1");
  if (p.exact_below < 0) throw Error("MatchParams: exact_below must be >= 0");
}

std::vector<DescriptorMatch> matchDescriptors(const cv::Mat& a, const cv::Mat& b, const MatchParams& params) {
  validate(params);
  if ((!a.empty() && a.type() != CV_32F) || (!b.empty() && b.type() != CV_32F))
    throw Error("matchDescriptors: descriptors must be CV_32F");
  std::vector<DescriptorMatch> out;
  if (a.empty() || b.rows < 2) return out;
  if (a.cols != b.cols)
    throw Error("matchDescriptors: descriptor widths differ (" + std::to_string(a.cols) + " vs " +
                std::to_string(b.cols) + ")");
  const bool exact = a.rows <= params.exact_below && b.rows <= params.exact_below;
  cv::Mat ab_idx, ab_dist;
  knn(a, b, 2, exact, params, ab_idx, ab_dist);
  cv::Mat ba_idx, ba_dist;
  if (params.mutual) knn(b, a, 1, exact, params, ba_idx, ba_dist);
  for (int i = 0; i < a.rows; ++i) {
    const int j = ab_idx.at<int>(i, 0);
    if (j < 0) continue;
    const float d1 = ab_dist.at<float>(i, 0), d2 = ab_dist.at<float>(i, 1);
    if (!(d1 <= static_cast<float>(params.ratio) * d2)) continue;
    if (params.mutual && ba_idx.at<int>(j, 0) != i) continue;
    out.push_back({i, j, d1});
  }
  return out;
}

}  // namespace gasp::baselines
