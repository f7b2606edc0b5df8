#pragma once
/// \file deskew_filter.h gasp-pairs --rolling-shutter: each depth image deskewed before GASP's
/// segmentation (rolling_shutter_deskew.h), with the velocity from GASP's registration of frames
/// i - 1 and i + 1 (the default) or, as a diagnostic, from the reference (--twist-from truth: its
/// samples nearest to 20 ms either side of the depth stamp + offset). Frames it cannot deskew are
/// used as loaded (said on stderr).
#include <opencv2/core.hpp>

#include <cstddef>
#include <set>
#include <vector>

#include "gasp/core/tum_dataset.h"
#include "gasp/pipeline/pair_registration.h"
#include "gasp/pipeline/rolling_shutter_deskew.h"

namespace gasp::pairs {

class DeskewFilter {
 public:
  enum class TwistFrom { kNeighbours, kTruth };
  /// `params` (GASP's) register the neighbours; `offset_s`: the reference's look-up offset.
  DeskewFilter(const TumDataset& ds, const DeskewParams& deskew, TwistFrom from, const PairParams& params,
               double offset_s)
      : ds_(ds), deskew_(deskew), from_(from), params_(params), offset_s_(offset_s) {}

  /// Frame i's depth [m], deskewed where it can be.
  cv::Mat operator()(std::size_t i, const cv::Mat& depth_m);

  std::size_t framesSeen() const { return frames_.size(); }
  std::size_t framesDeskewed() const { return deskewed_.size(); }
  /// Time per frame for the neighbours' registration and the deskew (neighbours only) [ms].
  const std::vector<double>& msPerFrame() const { return ms_; }

 private:
  const TumDataset& ds_;
  DeskewParams deskew_;
  TwistFrom from_;
  PairParams params_;
  double offset_s_;
  std::set<std::size_t> frames_, deskewed_;  ///< once each (a frame may be loaded again)
  std::vector<double> ms_;
};

}  // namespace gasp::pairs
