// fuzz_depth_png: the bytes as a .png file, read by the depth loader (gasp::loadDepthRaw /
// loadDepth, as TumDataset reads depth/*.png, with and without the expected size) and by the
// colour image reader (gasp::readImage, as TumDataset reads rgb/*.png). Seeds: small depth and
// rgb PNGs of the TUM folders and the simulator (fuzz/make_seeds.sh).
#include <cstddef>
#include <cstdint>

#include <opencv2/imgcodecs.hpp>

#include "fuzz_support.h"
#include "gasp/core/depth_image.h"
#include "gasp/core/image_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const gasp::fuzz::ScratchDir dir("depth_png");
  const std::string path = dir.write("input.png", data, size);
  gasp::fuzz::expectErrorsOnly([&] {
    const cv::Mat depth = gasp::loadDepth(path);  // loadDepthRaw + depthFromRaw
    static_cast<void>(gasp::countValidDepth(depth));
  });
  gasp::fuzz::expectErrorsOnly([&] { static_cast<void>(gasp::loadDepthRaw(path, 32, 24)); });
  gasp::fuzz::expectErrorsOnly([&] { static_cast<void>(gasp::readImage(path, cv::IMREAD_COLOR, "rgb image")); });
  return 0;
}
