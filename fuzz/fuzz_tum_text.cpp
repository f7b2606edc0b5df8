// fuzz_tum_text: GASP's readers of the TUM RGB-D text files. The first byte chooses the reader
// (its value modulo 4), the rest is the file:
//   0  a `timestamp filename` list (depth.txt, rgb.txt): gasp::readTumFileList
//   1  a trajectory (groundtruth.txt, estimates): gasp::readTumTrajectory, then findNearest and
//      associateTimestamps over its stamps
//   2  an intrinsics file: gasp::CameraIntrinsics::fromPresetOrFile (CameraIntrinsics::load)
//   3  a whole TUM folder: the rest split at lines "%%" into depth.txt, rgb.txt, groundtruth.txt
//      and intrinsics.txt (a missing part: no such file), opened with gasp::TumDataset::open,
//      which associates rgb and ground truth with the depth frames (associate.py's rule).
// No GASP reader reads associations.txt (TumDataset associates the lists itself), so it has no
// reader here. Seeds: fuzz/make_seeds.sh (the first lines of the TUM folders' files, the
// simulator's intrinsics.txt).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "gasp/core/camera_intrinsics.h"
#include "gasp/core/tum_dataset.h"
#include "gasp/core/tum_trajectory.h"

namespace {

/// `text` split at lines that are exactly "%%".
std::vector<std::string> splitParts(const std::string& text) {
  std::vector<std::string> parts(1);
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    const bool last = end == std::string::npos;
    if (last) end = text.size();
    const std::string line = text.substr(start, end - start);
    if (line == "%%") {
      parts.emplace_back();
    } else {
      parts.back() += line;
      if (!last) parts.back() += '\n';
    }
    if (last) break;
    start = end + 1;
  }
  return parts;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const gasp::fuzz::ScratchDir dir("tum_text");
  const int mode = data[0] % 4;
  const std::uint8_t* text = data + 1;
  const std::size_t length = size - 1;
  switch (mode) {
    case 0: {
      const std::string path = dir.write("depth.txt", text, length);
      gasp::fuzz::expectErrorsOnly([&] { static_cast<void>(gasp::readTumFileList(path)); });
      break;
    }
    case 1: {
      const std::string path = dir.write("groundtruth.txt", text, length);
      gasp::fuzz::expectErrorsOnly([&] {
        const gasp::Trajectory trajectory = gasp::readTumTrajectory(path);
        std::vector<double> stamps;
        for (const auto& p : trajectory) stamps.push_back(p.timestamp);
        for (double t : stamps) static_cast<void>(gasp::findNearest(trajectory, t + 0.01, 0.02));
        static_cast<void>(gasp::associateTimestamps(stamps, stamps, 0.02, 0.005));
      });
      break;
    }
    case 2: {
      const std::string path = dir.write("intrinsics.txt", text, length);
      gasp::fuzz::expectErrorsOnly([&] { static_cast<void>(gasp::CameraIntrinsics::fromPresetOrFile(path)); });
      break;
    }
    default: {
      const std::string folder = dir.path() + "/tum";
      std::error_code ec;
      std::filesystem::remove_all(folder, ec);
      std::filesystem::create_directories(folder);
      const auto parts = splitParts(std::string(reinterpret_cast<const char*>(text), length));
      const char* names[] = {"depth.txt", "rgb.txt", "groundtruth.txt", "intrinsics.txt"};
      for (std::size_t i = 0; i < parts.size() && i < 4; ++i)
        dir.write(std::string("tum/") + names[i], parts[i].data(), parts[i].size());
      gasp::fuzz::expectErrorsOnly([&] {
        const gasp::TumDataset ds = gasp::TumDataset::open(folder);
        static_cast<void>(ds.intrinsicsSummary());
        static_cast<void>(ds.countWithGroundTruth());
        for (std::size_t i = 0; i < ds.size(); ++i) static_cast<void>(ds.groundTruthOf(i, -0.03));
      });
      break;
    }
  }
  return 0;
}
