// The retry stage's rules (modules/pipeline/src/retry_policy.h, private to the pipeline; this test
// target has the module's src/ folder on its include path).
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "retry_policy.h"

namespace gasp {
namespace {

DepthView withDepth() {
  DepthView v;
  v.depth_m = cv::Mat(8, 8, CV_32FC1, cv::Scalar(1.0f));
  return v;
}

TEST(FinerScaleRetry, AppliesAfterAnUnobservableDenseProblemNotAfterADegeneratePatchProblem) {
  const DepthView a = withDepth(), b = withDepth();
  PairResult r;
  r.pose.success = false;
  EXPECT_TRUE(detail::finerScaleRetryApplies(r, a, b));
  r.pose.degenerate = true;  // a degenerate view or patch problem: no scale adds constraints
  EXPECT_FALSE(detail::finerScaleRetryApplies(r, a, b));
  r.dense_unobservable = true;  // the dense problem at RANSAC's pose: may be a wrong pose's
  EXPECT_TRUE(detail::finerScaleRetryApplies(r, a, b));
  r.pose.success = true;
  EXPECT_FALSE(detail::finerScaleRetryApplies(r, a, b));
  r.pose.success = false;
  EXPECT_FALSE(detail::finerScaleRetryApplies(r, a, DepthView{}));  // no depth to segment again
}

TEST(FinerScaleRetry, ReasonNamesTheFactor) {
  EXPECT_EQ(detail::finerScaleReason(0.3, "no consensus"), "at 0.3x the patch area: no consensus");
}

}  // namespace
}  // namespace gasp
