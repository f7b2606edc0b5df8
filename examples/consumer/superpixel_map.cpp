// GASP's MRPT layer from a downstream project: a superpixel map created from an ini section by
// MRPT's map factory, two synthetic frames (a wide baseline) as CObservation3DRangeScan, and
// their relative pose from gasp::CGaspAligner, checked against the simulator's ground truth.
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/maps/CMultiMetricMap.h>

#include <cstdio>

#include "gasp/mrpt/CGaspAligner.h"
#include "gasp/mrpt/CSuperpixelMap.h"
#include "gasp/rawlog/observation_conversion.h"
#include "gasp/sim/simulation.h"

namespace {

mrpt::obs::CObservation3DRangeScan::Ptr observation(const gasp::sim::SimulatedFrame& frame,
                                                    const gasp::CameraIntrinsics& intrinsics) {
  gasp::RgbdFrame rgbd;
  rgbd.timestamp = frame.timestamp;
  rgbd.depth_m = frame.depth;
  rgbd.depth_intrinsics = intrinsics;
  return gasp::observationFromFrame(rgbd);
}

}  // namespace

int main() {
  gasp::sim::SimulationOptions options;  // the synthetic room
  const gasp::sim::Simulation simulation(options);
  const auto a = simulation.frame(3), b = simulation.frame(9);

  // A CMultiMetricMap holding a gasp::CSuperpixelMap, as an MRPT application configures it.
  mrpt::maps::TSetOfMetricMapInitializers init;
  init.loadFromConfigFile(mrpt::config::CConfigFileMemory("[Maps]\nsuperpixelMap_count=1\n"
                                                          "[Maps_superpixelMap_00_creationOpts]\n"
                                                          "target_patch_area_m2=0.004\n"),
                          "Maps");
  mrpt::maps::CMultiMetricMap maps(init);
  const auto map_a = maps.mapByClass<gasp::CSuperpixelMap>();
  if (!map_a) return 1;
  map_a->insertObservation(*observation(a, options.intrinsics));
  gasp::CSuperpixelMap map_b;
  map_b.insertObservation(*observation(b, options.intrinsics));
  std::printf("superpixel_map_patches: %zu %zu\n", map_a->patchCount(), map_b.patchCount());

  gasp::CGaspAligner aligner;
  gasp::TGaspAlignmentResult info;
  const auto pdf = aligner.Align3DPDF(map_a.get(), &map_b, mrpt::poses::CPose3DPDFGaussian(), info);
  if (!pdf) {
    std::printf("no estimate: %s\n", info.reason.c_str());
    return 1;
  }
  // Both observations carry the same sensorPose S (the optical -> MRPT camera rotation), so the
  // robot frames relate as the cameras do, conjugated by S.
  const gasp::Isometry3 S = gasp::frameFromObservation(*observation(a, options.intrinsics), "a", gasp::ColourImage::Skip).T_robot_camera;
  const gasp::Isometry3 T_ra_rb = S * gasp::relativePose(a.T_world_camera, b.T_world_camera) * S.inverse();
  const gasp::Isometry3 error = T_ra_rb.inverse() * gasp::fromCPose3D(pdf->getMeanVal());
  std::printf("aligner_inliers: %d\naligner_error_m: %.4f\naligner_error_deg: %.3f\n", info.inliers,
              gasp::translationNorm(error), gasp::rotationAngle(error) * 180.0 / M_PI);
  return gasp::translationNorm(error) < 0.05 ? 0 : 1;
}
