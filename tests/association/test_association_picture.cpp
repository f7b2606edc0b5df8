// The association picture's legend (gasp/association/association_picture.h): counts, right and
// wrong against the truth, precision; drawn over the top of the picture.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include <vector>

#include "gasp/association/association_picture.h"
#include "gasp/core/error.h"

namespace gasp {
namespace {

TEST(AssociationPicture, LegendCountsRightAndWrongAgainstTheTruth) {
  EXPECT_EQ(associationLegend("verified", 4, {1, 1, 0, 1}),
            "verified associations: 4 -- 3 right, 1 wrong (precision 0.750); green right, red wrong");
  EXPECT_EQ(associationLegend("free", 3, {}), "free associations: 3 (no ground truth)");
  EXPECT_EQ(associationLegend("verified", 0, {}), "verified associations: 0");
}

TEST(AssociationPicture, TheLegendIsDrawnOverTheTopAndNothingElseChanges) {
  SuperpixelSegmentation a, b;
  a.labels = cv::Mat(48, 64, CV_32SC1, cv::Scalar(-1));
  b.labels = a.labels.clone();
  const cv::Mat depth(48, 64, CV_32FC1, cv::Scalar(1.0f));
  const CameraIntrinsics K = CameraIntrinsics::tumFreiburg1();
  const cv::Mat plain = drawAssociations(depth, a, K, depth, b, K, {});
  AssociationPictureOptions options;
  options.legend = associationLegend("verified", 0, {});
  const cv::Mat with = drawAssociations(depth, a, K, depth, b, K, {}, {}, options);
  ASSERT_EQ(with.size(), plain.size());
  const cv::Rect top(0, 0, plain.cols, 10), bottom(0, 30, plain.cols, 18);
  EXPECT_GT(cv::norm(with(top), plain(top), cv::NORM_L1), 0.0);
  EXPECT_EQ(cv::norm(with(bottom), plain(bottom), cv::NORM_L1), 0.0);
  EXPECT_THROW(drawAssociations(depth, a, K, depth, b, K, {{0, 0, 0.1}}), Error);  // no such patch
}

}  // namespace
}  // namespace gasp
