#include "gasp/eval/precision_recall.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "gasp/core/error.h"

namespace gasp::eval {

std::vector<PrPoint> precisionRecallCurve(const std::vector<ScoredDetection>& detections, std::size_t positives) {
  std::vector<ScoredDetection> sorted = detections;
  std::size_t correct = 0;
  for (const ScoredDetection& d : sorted) {
    if (!std::isfinite(d.score)) throw Error("precision-recall: a detection's score is not finite");
    correct += d.correct ? 1 : 0;
  }
  if (correct > positives)
    throw Error("precision-recall: " + std::to_string(correct) + " correct detections, more than the " +
                std::to_string(positives) + " positives");
  std::sort(sorted.begin(), sorted.end(), [](const ScoredDetection& a, const ScoredDetection& b) { return a.score > b.score; });
  std::vector<PrPoint> curve;
  PrPoint p;
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    (sorted[i].correct ? p.true_positives : p.false_positives) += 1;
    if (i + 1 < sorted.size() && sorted[i + 1].score == sorted[i].score) continue;  // ties enter together
    p.threshold = sorted[i].score;
    p.precision = static_cast<double>(p.true_positives) / static_cast<double>(p.true_positives + p.false_positives);
    p.recall = positives > 0 ? static_cast<double>(p.true_positives) / static_cast<double>(positives) : 0.0;
    curve.push_back(p);
  }
  return curve;
}

double recallAtFullPrecision(const std::vector<PrPoint>& curve, double* threshold) {
  double best = 0.0, at = std::numeric_limits<double>::infinity();
  for (const PrPoint& p : curve)
    if (p.false_positives == 0 && p.recall >= best && p.true_positives > 0) best = p.recall, at = p.threshold;
  if (threshold) *threshold = at;
  return best;
}

}  // namespace gasp::eval
