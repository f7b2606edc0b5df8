// fuzz_rawlog: the bytes as a rawlog file (gzip-compressed or plain: the reader takes both), read
// to its end with gasp::RawlogReader, every frame converted (frameFromObservation) and its pixels
// touched. Seeds: fuzz/make_seeds.sh (tiny rawlogs from gasp-tum2rawlog over a few frames of the
// TUM folders and of the simulator, compressed and plain).
#include <cstddef>
#include <cstdint>

#include <opencv2/core.hpp>

#include "fuzz_support.h"
#include "gasp/core/depth_image.h"
#include "gasp/rawlog/rawlog_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const gasp::fuzz::ScratchDir dir("rawlog");
  const std::string path = dir.write("input.rawlog", data, size);
  gasp::fuzz::expectErrorsOnly([&] {
    gasp::RawlogReader reader(path);
    std::size_t checksum = 0;
    while (auto frame = reader.next()) {
      checksum += gasp::countValidDepth(frame->depth_m);  // every depth pixel read (ASan checks the buffer)
      if (frame->hasRgb()) checksum += static_cast<std::size_t>(cv::sum(frame->rgb)[0]);
      if (!frame->depth_raw.empty()) checksum += static_cast<std::size_t>(cv::sum(frame->depth_raw)[0]);
    }
    static_cast<void>(reader.skippedSummary());
    static_cast<void>(checksum);
  });
  return 0;
}
