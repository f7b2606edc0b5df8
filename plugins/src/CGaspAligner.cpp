#include "gasp/mrpt/CGaspAligner.h"

#include <mrpt/core/exceptions.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <chrono>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "gasp/core/stopwatch.h"
#include "gasp/mrpt/CSuperpixelMap.h"
#include "gasp/mrpt/params_io.h"
#include "gasp/rawlog/observation_conversion.h"

IMPLEMENTS_MRPT_OBJECT(CGaspAligner, mrpt::rtti::CObject, gasp)

namespace gasp {

namespace {

/// The superpixel map to align: m itself, or the one inside a CMultiMetricMap (CSuperpixelMap::findIn).
const CSuperpixelMap& asSuperpixelMap(const mrpt::maps::CMetricMap* m, const char* which) {
  std::string why;
  const CSuperpixelMap* s = CSuperpixelMap::findIn(m, &why);
  if (!s) THROW_EXCEPTION_FMT("gasp::CGaspAligner: map %s cannot be aligned: %s", which, why.c_str());
  return *s;
}

/// Fills the caller's result (extended fields when it is a TGaspAlignmentResult).
void report(mrpt::optional_ref<mrpt::slam::TMetricMapAlignmentResult> out, const TGaspAlignmentResult& r) {
  if (!out) return;
  if (auto* g = dynamic_cast<TGaspAlignmentResult*>(&out->get()))
    *g = r;
  else
    out->get().executionTime = r.executionTime;
}

}  // namespace

void CGaspAligner::TOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                                                const std::string& section) {
  readPairParams(source, section, params);
}

void CGaspAligner::TOptions::saveToConfigFile(mrpt::config::CConfigFileBase& target,
                                              const std::string& section) const {
  writePairParams(params, target, section);
}

CGaspAligner::CGaspAligner() { setLoggerName("gasp::CGaspAligner"); }

mrpt::poses::CPose3DPDF::Ptr CGaspAligner::Align3DPDF(const mrpt::maps::CMetricMap* m1,
                                                       const mrpt::maps::CMetricMap* m2,
                                                       const mrpt::poses::CPose3DPDFGaussian& /*initial*/,
                                                       mrpt::optional_ref<mrpt::slam::TMetricMapAlignmentResult> outInfo) {
  const auto t0 = std::chrono::steady_clock::now();
  const CSuperpixelMap& map1 = asSuperpixelMap(m1, "m1");
  const CSuperpixelMap& map2 = asSuperpixelMap(m2, "m2");
  TGaspAlignmentResult best;
  std::optional<mrpt::poses::CPose3DPDFGaussian> best_pdf;
  if (map1.isEmpty() || map2.isEmpty()) best.reason = std::string("map ") + (map1.isEmpty() ? "m1" : "m2") + " is empty";
  int best_failed_inliers = -1;
  // One registration's outcome, kept when it beats the best so far: a default-scale pose before
  // one from the finer-scale retry (whose smaller patches give more inliers for the same
  // surface), then the most inliers; without any pose, the most promising failure (its reason is
  // the informative one).
  const auto consider = [&](std::size_t i, std::size_t j, const PairResult& r, bool finer_scale) {
    const SuperpixelMapView& vi = map1.views()[i];
    const SuperpixelMapView& vj = map2.views()[j];
    TGaspAlignmentResult cand;
    cand.view_m1 = static_cast<int>(i);
    cand.view_m2 = static_cast<int>(j);
    // The finer-scale views' patch indices are not the maps' patches.
    cand.finer_scale = finer_scale;
    if (!finer_scale)
      for (const auto& s : r.association.associations) cand.associations.emplace_back(s.b, s.a);
    cand.inliers = r.pose.num_inliers;
    cand.degenerate = r.pose.degenerate;
    cand.reason = r.pose.reason;
    std::optional<mrpt::poses::CPose3DPDFGaussian> pdf;
    if (r.pose.success) {
      const Isometry3 T_m1_m2 = vi.T_map_camera * r.pose.T_target_source * vj.T_map_camera.inverse();
      cand.information = informationInFrame(r.edge_information, vi.T_map_camera);
      pdf = poseWithInformation(T_m1_m2, cand.information);
      if (!pdf) {
        cand.degenerate = true;
        cand.reason = "the pose's information matrix is not positive definite";
        cand.information.setZero();
      }
    }
    cand.success = pdf.has_value();
    const bool better = !best.success || (cand.finer_scale != best.finer_scale ? !cand.finer_scale
                                                                              : cand.inliers > best.inliers);
    const int pairs = best.view_pairs;
    if (cand.success && better) {
      best = std::move(cand);
      best_pdf = pdf;
    } else if (!best.success && cand.inliers > best_failed_inliers) {
      best_failed_inliers = cand.inliers;
      best = std::move(cand);
    }
    best.view_pairs = pairs;
  };

  // Every view pair at the default scale first (source: m2's view, target: m1's view, so
  // T_target_source = T_ci_cj). The finer-scale retry (PairParams::retry_area_factor) runs only
  // when none gives a pose -- a default-scale pose would be preferred anyway -- and then
  // re-segments each view once instead of once per pair.
  PairParams default_scale = options.params;
  default_scale.retry_area_factor = 0.0;
  std::vector<std::pair<std::size_t, std::size_t>> retry_pairs;
  for (std::size_t i = 0; i < map1.views().size(); ++i) {
    for (std::size_t j = 0; j < map2.views().size(); ++j) {
      ++best.view_pairs;
      const DepthView& source = map2.views()[j].view;
      const DepthView& target = map1.views()[i].view;
      const PairResult r = registerViews(source, target, default_scale);
      if (finerScaleRetryApplies(r, source, target)) retry_pairs.emplace_back(i, j);
      consider(i, j, r, false);
    }
  }
  const double factor = options.params.retry_area_factor;
  if (!best.success && factor > 0.0 && !retry_pairs.empty()) {
    // Each view re-segmented at most once; nullopt: its second segmentation threw (logged, and
    // its pairs are not retried).
    std::map<std::size_t, std::optional<DepthView>> fine1, fine2;
    const auto fine = [&](std::map<std::size_t, std::optional<DepthView>>& cache, const CSuperpixelMap& map,
                          const char* name, std::size_t k) -> const std::optional<DepthView>& {
      auto it = cache.find(k);
      if (it != cache.end()) return it->second;
      std::optional<DepthView> v;
      try {
        v = finerScaleView(map.views()[k].view, factor);
      } catch (const std::exception& e) {
        logFmt(mrpt::system::LVL_WARN, "%s view %zu: %s", name, k,
               finerScaleReason(factor, std::string("segmentation failed: ") + e.what()).c_str());
      }
      return cache.emplace(k, std::move(v)).first->second;
    };
    const PairParams finer = finerScaleParams(options.params);
    for (const auto& [i, j] : retry_pairs) {
      const auto& target = fine(fine1, map1, "m1", i);
      const auto& source = fine(fine2, map2, "m2", j);
      if (!source || !target) continue;
      PairResult r = registerViews(*source, *target, finer);
      r.pose.reason = finerScaleReason(factor, r.pose.reason);
      consider(i, j, r, true);
    }
  }
  if (!best.success && best.reason.empty()) best.reason = "no view pair gave an estimate";
  best.time_ms = msSince(t0);
  best.executionTime = best.time_ms / 1000.0;
  report(outInfo, best);
  if (!best.success) {
    logFmt(mrpt::system::LVL_DEBUG, "no estimate: %s", best.reason.c_str());
    return nullptr;
  }
  return mrpt::poses::CPose3DPDFGaussian::Create(*best_pdf);
}

mrpt::poses::CPosePDF::Ptr CGaspAligner::AlignPDF(const mrpt::maps::CMetricMap* m1, const mrpt::maps::CMetricMap* m2,
                                                   const mrpt::poses::CPosePDFGaussian& initialEstimationPDF,
                                                   mrpt::optional_ref<mrpt::slam::TMetricMapAlignmentResult> outInfo) {
  mrpt::poses::CPose3DPDFGaussian initial;
  initial.copyFrom(initialEstimationPDF);
  const auto pdf3 = Align3DPDF(m1, m2, initial, outInfo);
  if (!pdf3) return nullptr;
  return mrpt::poses::CPosePDFGaussian::Create(*pdf3);
}

mrpt::poses::CPose3DPDFGaussian::Ptr CGaspAligner::alignObservations(
    const mrpt::obs::CObservation& a, const mrpt::obs::CObservation& b,
    mrpt::optional_ref<mrpt::slam::TMetricMapAlignmentResult> outInfo) {
  CSuperpixelMap map_a, map_b;
  for (auto* m : {&map_a, &map_b}) m->creationOptions.superpixels = options.params.superpixels;
  if (!map_a.insertObservation(a) || !map_b.insertObservation(b)) {
    const auto& bad = map_a.isEmpty() ? a : b;
    THROW_EXCEPTION_FMT("gasp::CGaspAligner: observation %s is a %s; only mrpt::obs::CObservation3DRangeScan "
                        "(RGB-D or range-only) is supported",
                        map_a.isEmpty() ? "a" : "b", bad.GetRuntimeClass()->className);
  }
  const auto pdf = Align3DPDF(&map_a, &map_b, mrpt::poses::CPose3DPDFGaussian(), outInfo);
  return std::dynamic_pointer_cast<mrpt::poses::CPose3DPDFGaussian>(pdf);
}

}  // namespace gasp
