#include <gtest/gtest.h>

#include <cmath>

#include "gasp/eval/error_statistics.h"

TEST(ErrorStatistics, MatchesNumpyDefinitions) {
  const auto s = gasp::eval::computeStatistics({3.0, 1.0, 4.0, 2.0});
  EXPECT_EQ(s.count, 4u);
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.median, 2.5);  // mean of the middle two
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(30.0 / 4.0));
  EXPECT_DOUBLE_EQ(s.std, std::sqrt(1.25));  // population std
  EXPECT_DOUBLE_EQ(s.min, 1.0);
  EXPECT_DOUBLE_EQ(s.max, 4.0);
  EXPECT_DOUBLE_EQ(gasp::eval::computeStatistics({5.0, 1.0, 2.0}).median, 2.0);
  EXPECT_EQ(gasp::eval::computeStatistics({}).count, 0u);
}
