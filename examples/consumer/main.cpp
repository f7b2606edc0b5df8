// Renders one synthetic frame, decomposes it into surface patches, and round-trips it through
// an MRPT observation: proof that the installed gasp:: targets link and work together.
#include <cstdio>

#include "gasp/rawlog/observation_conversion.h"
#include "gasp/sim/simulation.h"
#include "gasp/superpixels/depth_superpixels.h"

int main() {
  gasp::sim::SimulationOptions options;
  options.scene = "sparse";
  options.frames = 8;
  const gasp::sim::Simulation simulation(options);
  const auto frame = simulation.frame(0);
  const auto segmentation = gasp::segmentDepthSuperpixels(frame.depth, options.intrinsics);
  gasp::RgbdFrame rgbd;
  rgbd.timestamp = frame.timestamp;
  rgbd.depth_m = frame.depth;
  rgbd.depth_intrinsics = options.intrinsics;
  const auto observation = gasp::observationFromFrame(rgbd);
  const auto back = gasp::frameFromObservation(*observation);
  double max_error_m = 0.0;
  cv::minMaxLoc(cv::abs(back.depth_m - frame.depth), nullptr, &max_error_m);
  std::printf("patches: %zu\ncoverage: %.3f\nmrpt_round_trip_max_error_m: %g\n", segmentation.patches.size(),
              segmentation.stats.coverage(), max_error_m);
  return segmentation.patches.empty() ? 1 : 0;
}
