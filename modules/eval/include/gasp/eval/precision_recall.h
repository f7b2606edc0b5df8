#pragma once
/// \file precision_recall.h Precision and recall of a detector whose detections carry a score:
/// each threshold on the score accepts the detections at or above it; precision = the accepted
/// that are correct over the accepted, recall = the accepted that are correct over the positives
/// (the cases that have a correct answer to find, detected or not).
#include <cstddef>
#include <vector>

namespace gasp::eval {

struct ScoredDetection {
  double score = 0.0;    ///< higher = surer
  bool correct = false;  ///< true by the reference
};

/// One point of the curve: the detections with score >= threshold accepted.
struct PrPoint {
  double threshold = 0.0;
  std::size_t true_positives = 0;
  std::size_t false_positives = 0;
  double precision = 1.0;  ///< 1 when nothing is accepted
  double recall = 0.0;
};

/// The curve over every distinct score, highest threshold first (recall non-decreasing). Throws
/// gasp::Error for a non-finite score, or more correct detections than `positives`.
std::vector<PrPoint> precisionRecallCurve(const std::vector<ScoredDetection>& detections, std::size_t positives);

/// The highest recall among the points with no false positive (0 when there is none): the recall
/// at 100 % precision. Its point's threshold in `threshold` when given (+infinity for none).
double recallAtFullPrecision(const std::vector<PrPoint>& curve, double* threshold = nullptr);

}  // namespace gasp::eval
