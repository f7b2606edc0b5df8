// gasp_rawlog_to_simplemap IN.rawlog GROUND_TRUTH.txt OUT.simplemap [EVERY]
// Pairs the CObservation3DRangeScan of a rawlog (e.g. written by gasp-tum2rawlog) with the
// ground-truth camera poses of a TUM trajectory (gasp-tum2rawlog's OUT_groundtruth.txt) and
// writes an MRPT simplemap (robot pose + sensory frame per scan), the input of MRPT's
// observations2map. Robot pose = camera pose * sensorPose^-1 (optical frames as GASP converts them).
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/maps/CSimpleMap.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose3DPDFGaussian.h>
#include <mrpt/serialization/CArchive.h>

#include <cstdio>
#include <string>

#include "gasp/core/tum_trajectory.h"
#include "gasp/rawlog/observation_conversion.h"

int main(int argc, char** argv) {
  if (argc != 4 && argc != 5) {
    std::fprintf(stderr, "usage: %s IN.rawlog GROUND_TRUTH.txt OUT.simplemap [EVERY]\n", argv[0]);
    return 2;
  }
  try {
    const int every = argc == 5 ? std::stoi(argv[4]) : 1;
    if (every < 1) throw std::runtime_error("EVERY must be >= 1");
    const gasp::Trajectory gt = gasp::readTumTrajectory(argv[2]);
    mrpt::maps::CSimpleMap simplemap;
    mrpt::io::CFileGZInputStream in_file(argv[1]);
    auto in = mrpt::serialization::archiveFrom(in_file);
    int scans = 0, kept = 0;
    for (;;) {
      mrpt::serialization::CSerializable::Ptr object;
      try {
        in >> object;
      } catch (const std::exception&) {
        break;  // end of the rawlog
      }
      const auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(object);
      if (!scan || scans++ % every != 0) continue;
      const auto k = gasp::findNearest(gt, mrpt::Clock::toDouble(scan->timestamp), 0.02);
      if (!k) continue;  // no ground truth for this scan
      const gasp::Isometry3 S = gasp::frameFromObservation(*scan, "scan", gasp::ColourImage::Skip).T_robot_camera;
      const auto pose = mrpt::poses::CPose3DPDFGaussian::Create(gasp::toCPose3D(gt[*k].T_world_camera * S.inverse()));
      auto sf = mrpt::obs::CSensoryFrame::Create();
      sf->insert(scan);
      simplemap.insert(pose, sf);
      ++kept;
    }
    mrpt::io::CFileGZOutputStream out_file(argv[3]);
    mrpt::serialization::archiveFrom(out_file) << simplemap;
    std::printf("scans: %d\nkept: %d\nsimplemap: %s\n", scans, kept, argv[3]);
    return kept > 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
