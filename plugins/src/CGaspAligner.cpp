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
#include "gasp/params/params_io.h"
#include "gasp/pipeline/range_view.h"
#include "gasp/rawlog/observation_conversion.h"
#include "gasp/rawlog/range_scan.h"

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
  PairParams p = params;  // both read, or neither changed
  LidarParams l = lidar;
  readPairParams(source, section, p, lidarKeys());
  readLidarParams(source, section, l, pairKeys());
  params = p;
  lidar = l;
}

void CGaspAligner::TOptions::saveToConfigFile(mrpt::config::CConfigFileBase& target,
                                              const std::string& section) const {
  writePairParams(params, target, section);
  writeLidarParams(lidar, target, section);
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
  if (map1.isEmpty() || map2.isEmpty()) best.reason = std::string("map ") + (map1.isEmpty() ? "m1" : "m2") + " is empty";
  // Source: m2's views, target: m1's views, so that T_target_source = T_ci_cj. The pipeline
  // decides which registration is the answer and when the finer-scale retry runs
  // (registerViewSets); here it is only turned into MRPT's terms.
  std::vector<const DepthView*> sources, targets;
  for (const auto& v : map2.views()) sources.push_back(&v.view);
  for (const auto& v : map1.views()) targets.push_back(&v.view);
  // Depth images' views with options.params, LiDAR sweeps' with the LiDAR's values; not both.
  std::size_t sweeps = 0;
  for (const auto* views : {&sources, &targets})
    for (const DepthView* v : *views) sweeps += v->returns ? 1 : 0;
  const bool lidar = sweeps > 0;
  if (lidar && sweeps != sources.size() + targets.size()) {
    sources.clear(), targets.clear();
    best.reason = "the maps hold both LiDAR sweeps' and depth images' views (" + std::to_string(sweeps) + " of " +
                  std::to_string(map1.views().size() + map2.views().size()) + " are sweeps): one kind of view per alignment";
  }
  const ViewSetResult set = registerViewSets(sources, targets, lidar ? lidarPairParams(options.lidar, options.params) : options.params);
  for (const auto& note : set.notes) logFmt(mrpt::system::LVL_WARN, "%s", note.c_str());
  best.view_pairs = static_cast<int>(sources.size() * targets.size());
  std::optional<mrpt::poses::CPose3DPDFGaussian> pdf;
  if (set.best >= 0) {
    const ViewSetRegistration& reg = set.registrations[static_cast<std::size_t>(set.best)];
    const PairResult& r = reg.result;
    const SuperpixelMapView& vi = map1.views()[reg.target];
    const SuperpixelMapView& vj = map2.views()[reg.source];
    best.view_m1 = static_cast<int>(reg.target);
    best.view_m2 = static_cast<int>(reg.source);
    best.finer_scale = reg.finer_scale;  // the finer-scale views' patch indices are not the maps' patches
    if (!reg.finer_scale)
      for (const auto& s : r.association.associations) best.associations.emplace_back(s.b, s.a);
    best.inliers = r.pose.num_inliers;
    best.degenerate = r.pose.degenerate;
    best.reason = r.pose.reason;
    // An alignment is a full pose: a partial one (certify_stage.h) is no estimate here.
    if (r.pose.partial) best.reason = "degenerate scene: only a " + r.pose.reason + " (an alignment needs a full pose)";
    if (r.pose.success) {
      const Isometry3 T_m1_m2 = vi.T_map_camera * r.pose.T_target_source * vj.T_map_camera.inverse();
      best.information = informationInFrame(r.edge_information, vi.T_map_camera);
      pdf = poseWithInformation(T_m1_m2, best.information);
      if (!pdf) {
        best.degenerate = true;
        best.reason = "the pose's information matrix is not positive definite";
        best.information.setZero();
      }
    }
    best.success = pdf.has_value();
  }
  if (!best.success && best.reason.empty()) best.reason = "no view pair gave an estimate";
  best.time_ms = msSince(t0);
  best.executionTime = best.time_ms / 1000.0;
  report(outInfo, best);
  if (!best.success) {
    logFmt(mrpt::system::LVL_DEBUG, "no estimate: %s", best.reason.c_str());
    return nullptr;
  }
  return mrpt::poses::CPose3DPDFGaussian::Create(*pdf);
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
  for (auto* m : {&map_a, &map_b}) {
    m->creationOptions.superpixels = options.params.segment;
    m->creationOptions.lidar = options.lidar;
  }
  if (!map_a.insertObservation(a) || !map_b.insertObservation(b)) {
    const auto& bad = map_a.isEmpty() ? a : b;
    THROW_EXCEPTION_FMT("gasp::CGaspAligner: observation %s is a %s; only mrpt::obs::CObservation3DRangeScan "
                        "(RGB-D or range-only), CObservationRotatingScan, CObservationVelodyneScan and CObservationPointCloud are supported",
                        map_a.isEmpty() ? "a" : "b", bad.GetRuntimeClass()->className);
  }
  if (isSweepObservation(a) != isSweepObservation(b))
    THROW_EXCEPTION_FMT("gasp::CGaspAligner: observation a is %s, b %s: both must be depth images or both LiDAR sweeps",
                        observationKind(a).c_str(), observationKind(b).c_str());
  const auto pdf = Align3DPDF(&map_a, &map_b, mrpt::poses::CPose3DPDFGaussian(), outInfo);
  return std::dynamic_pointer_cast<mrpt::poses::CPose3DPDFGaussian>(pdf);
}

}  // namespace gasp
