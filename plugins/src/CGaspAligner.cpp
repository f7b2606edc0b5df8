#include "gasp/mrpt/CGaspAligner.h"

#include <mrpt/core/exceptions.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <chrono>

#include "gasp/mrpt/CSuperpixelMap.h"
#include "gasp/mrpt/params_io.h"
#include "gasp/rawlog/observation_conversion.h"

IMPLEMENTS_MRPT_OBJECT(CGaspAligner, mrpt::rtti::CObject, gasp)

namespace gasp {

namespace {

const CSuperpixelMap& asSuperpixelMap(const mrpt::maps::CMetricMap* m, const char* which) {
  if (!m) THROW_EXCEPTION_FMT("gasp::CGaspAligner: map %s is null", which);
  const auto* s = dynamic_cast<const CSuperpixelMap*>(m);
  if (!s) {
    THROW_EXCEPTION_FMT("gasp::CGaspAligner: map %s is a %s; only gasp::CSuperpixelMap can be aligned", which,
                        m->GetRuntimeClass()->className);
  }
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
  for (std::size_t i = 0; i < map1.views().size(); ++i) {
    const SuperpixelMapView& vi = map1.views()[i];
    for (std::size_t j = 0; j < map2.views().size(); ++j) {
      const SuperpixelMapView& vj = map2.views()[j];
      ++best.view_pairs;
      // Source: m2's view, target: m1's view, so T_target_source = T_ci_cj.
      const PairResult r = registerViews(vj.view, vi.view, options.params);
      TGaspAlignmentResult cand;
      cand.view_m1 = static_cast<int>(i);
      cand.view_m2 = static_cast<int>(j);
      // The finer-scale retry's patch indices refer to its own views, not to the maps' patches.
      cand.finer_scale = r.retry_views != nullptr;
      if (!cand.finer_scale)
        for (const auto& s : r.association.associations) cand.associations.emplace_back(s.b, s.a);
      cand.inliers = r.pose.num_inliers;
      cand.degenerate = r.pose.degenerate;
      cand.reason = r.pose.reason;
      std::optional<mrpt::poses::CPose3DPDFGaussian> pdf;
      if (r.pose.success) {
        const Isometry3 T_m1_m2 = vi.T_map_camera * r.pose.T_target_source * vj.T_map_camera.inverse();
        cand.information = informationInFrame(r.pose.information, vi.T_map_camera);
        pdf = poseWithInformation(T_m1_m2, cand.information);
        if (!pdf) {
          cand.degenerate = true;
          cand.reason = "the refinement's information matrix is not positive definite";
          cand.information.setZero();
        }
      }
      cand.success = pdf.has_value();
      // Best: a default-scale pose before one from the finer-scale retry (whose smaller patches
      // give more inliers for the same surface), then the most inliers.
      const bool better = !best.success || (cand.finer_scale != best.finer_scale ? !cand.finer_scale
                                                                                : cand.inliers > best.inliers);
      if (cand.success && better) {
        const int pairs = best.view_pairs;
        best = std::move(cand);
        best.view_pairs = pairs;
        best_pdf = pdf;
      } else if (!best.success && cand.inliers > best_failed_inliers) {
        // Keep the most promising failure, so that the reason is the informative one.
        best_failed_inliers = cand.inliers;
        const int pairs = best.view_pairs;
        best = std::move(cand);
        best.view_pairs = pairs;
      }
    }
  }
  if (!best.success && best.reason.empty()) best.reason = "no view pair gave an estimate";
  best.time_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
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
