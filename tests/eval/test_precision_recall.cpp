// Precision and recall of scored detections (gasp/eval/precision_recall.h).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "gasp/core/error.h"
#include "gasp/eval/precision_recall.h"

using gasp::eval::ScoredDetection;

TEST(PrecisionRecall, EachThresholdAcceptsTheScoresAtOrAboveIt) {
  // Scores 9 (correct), 7 (wrong), 7 (correct), 3 (correct); 5 positives (two never detected).
  const auto curve = gasp::eval::precisionRecallCurve({{3, true}, {7, false}, {9, true}, {7, true}}, 5);
  ASSERT_EQ(curve.size(), 3u);  // the tie at 7 is one point
  EXPECT_EQ(curve[0].threshold, 9);
  EXPECT_EQ(curve[0].true_positives, 1u);
  EXPECT_DOUBLE_EQ(curve[0].precision, 1.0);
  EXPECT_DOUBLE_EQ(curve[0].recall, 0.2);
  EXPECT_EQ(curve[1].threshold, 7);
  EXPECT_EQ(curve[1].false_positives, 1u);
  EXPECT_DOUBLE_EQ(curve[1].precision, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(curve[1].recall, 0.4);
  EXPECT_DOUBLE_EQ(curve[2].precision, 0.75);
  EXPECT_DOUBLE_EQ(curve[2].recall, 0.6);
  double threshold = 0;
  EXPECT_DOUBLE_EQ(gasp::eval::recallAtFullPrecision(curve, &threshold), 0.2);
  EXPECT_EQ(threshold, 9);
}

TEST(PrecisionRecall, NoCorrectDetectionAtFullPrecisionIsRecallZero) {
  const auto curve = gasp::eval::precisionRecallCurve({{5, false}, {4, true}}, 1);
  double threshold = 0;
  EXPECT_EQ(gasp::eval::recallAtFullPrecision(curve, &threshold), 0.0);
  EXPECT_TRUE(std::isinf(threshold));
  EXPECT_TRUE(gasp::eval::precisionRecallCurve({}, 3).empty());
}

TEST(PrecisionRecall, BadInputIsAnError) {
  EXPECT_THROW(gasp::eval::precisionRecallCurve({{1, true}, {2, true}}, 1), gasp::Error);
  EXPECT_THROW(gasp::eval::precisionRecallCurve({{std::nan(""), true}}, 1), gasp::Error);
  EXPECT_THROW(gasp::eval::precisionRecallCurve({{std::numeric_limits<double>::infinity(), true}}, 1), gasp::Error);
}
