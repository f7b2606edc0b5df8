// Descriptor matching: nearest neighbour, ratio test, mutual check, exact and FLANN paths.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include <numeric>
#include <random>

#include "gasp/baselines/descriptor_matching.h"
#include "gasp/core/error.h"

namespace gb = gasp::baselines;

namespace {

/// n random descriptors of width w in [0, 1), and a noisy copy permuted by perm (row i of b is
/// row perm[i] of a).
void makePair(int n, int w, double noise, cv::Mat& a, cv::Mat& b, std::vector<int>& perm) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  std::normal_distribution<float> gauss(0.0f, static_cast<float>(noise));
  a.create(n, w, CV_32F);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < w; ++j) a.at<float>(i, j) = uni(rng);
  perm.resize(static_cast<std::size_t>(n));
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), rng);
  b.create(n, w, CV_32F);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < w; ++j) b.at<float>(i, j) = a.at<float>(perm[static_cast<std::size_t>(i)], j) + gauss(rng);
}

void expectAllCorrect(const std::vector<gb::DescriptorMatch>& m, const std::vector<int>& perm, int n) {
  ASSERT_EQ(static_cast<int>(m.size()), n);
  for (const auto& x : m) EXPECT_EQ(perm[static_cast<std::size_t>(x.b)], x.a);
}

}  // namespace

TEST(DescriptorMatching, ExactSearchFindsEveryPermutedRow) {
  cv::Mat a, b;
  std::vector<int> perm;
  makePair(300, 32, 0.01, a, b, perm);
  expectAllCorrect(gb::matchDescriptors(a, b), perm, 300);
}

TEST(DescriptorMatching, FlannSearchFindsEveryPermutedRowAndRepeats) {
  cv::Mat a, b;
  std::vector<int> perm;
  makePair(3000, 64, 0.01, a, b, perm);
  gb::MatchParams p;
  p.exact_below = 100;  // force the KD-tree path
  const auto m1 = gb::matchDescriptors(a, b, p);
  expectAllCorrect(m1, perm, 3000);
  const auto m2 = gb::matchDescriptors(a, b, p);
  ASSERT_EQ(m1.size(), m2.size());
  for (std::size_t i = 0; i < m1.size(); ++i) EXPECT_EQ(m1[i].b, m2[i].b);
}

TEST(DescriptorMatching, RatioTestRejectsAmbiguousPartners) {
  // Row 0 of A has two near-identical partners in B: the ratio test must drop it; row 1 is clear.
  cv::Mat a = (cv::Mat_<float>(2, 2) << 0, 0, 10, 10);
  cv::Mat b = (cv::Mat_<float>(3, 2) << 1, 0, 0, 1.05f, 10, 10.1f);
  const auto m = gb::matchDescriptors(a, b);
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0].a, 1);
  EXPECT_EQ(m[0].b, 2);
  EXPECT_NEAR(m[0].distance, 0.1f, 1e-5);
  gb::MatchParams loose;
  loose.ratio = 1.0;
  EXPECT_EQ(gb::matchDescriptors(a, b, loose).size(), 2u);
}

TEST(DescriptorMatching, MutualCheckRejectsOneWayPartners) {
  // A0 and A1 both have B0 as nearest; only A1 is B0's nearest.
  cv::Mat a = (cv::Mat_<float>(2, 1) << 0.0f, 0.9f);
  cv::Mat b = (cv::Mat_<float>(2, 1) << 1.0f, 100.0f);
  gb::MatchParams p;
  p.ratio = 1.0;
  const auto m = gb::matchDescriptors(a, b, p);
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0].a, 1);
  p.mutual = false;
  EXPECT_EQ(gb::matchDescriptors(a, b, p).size(), 2u);
}

TEST(DescriptorMatching, BadInput) {
  cv::Mat a(3, 4, CV_32F, cv::Scalar(0)), b(3, 5, CV_32F, cv::Scalar(0)), d(3, 4, CV_64F, cv::Scalar(0));
  EXPECT_THROW(gb::matchDescriptors(a, b), gasp::Error);
  EXPECT_THROW(gb::matchDescriptors(a, d), gasp::Error);
  gb::MatchParams p;
  p.ratio = 0;
  EXPECT_THROW(gb::matchDescriptors(a, a, p), gasp::Error);
  EXPECT_TRUE(gb::matchDescriptors(a, cv::Mat(1, 4, CV_32F, cv::Scalar(0))).empty());  // no second neighbour
  EXPECT_TRUE(gb::matchDescriptors(cv::Mat(), a).empty());
}
