#pragma once
/// \file image_header.h (private) The pixel count an image file's header declares, checked
/// against what a file of its size can hold, before OpenCV allocates the image.
///
/// cv::imread() allocates the whole image from the header's width and height before it decodes
/// the pixels: a 53-byte JPEG declaring 64255 x 13568 pixels made it allocate 2.6 GB (found by
/// fuzz_depth_png) and a PNG header can do the same. A compressed stream has a largest ratio:
/// zlib's deflate (PNG) expands at most 1032 times, and a Huffman-coded JPEG spends at least one
/// bit per 8 x 8 block of its first component; an image that needs more than that from the file's
/// bytes cannot be in the file (a corrupt or cut header). Checked: PNG (IHDR) and Huffman JPEG
/// (SOF0-3, 5-7). Other formats (arithmetic-coded JPEG, TIFF, BMP, PNM, WebP, JPEG 2000, ...) are
/// left to OpenCV, which refuses more than 2^30 pixels.
#include <algorithm>
#include <array>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace gasp::detail {

inline std::uint32_t bigEndian(const unsigned char* p, int bytes) {
  std::uint32_t v = 0;
  for (int i = 0; i < bytes; ++i) v = (v << 8) | p[i];
  return v;
}

/// "" or why the header of `path` (of `file_size` bytes) declares more pixels than the file holds.
inline std::string imageHeaderProblem(const std::string& path, std::uint64_t file_size) {
  std::ifstream in(path, std::ios::binary);
  std::array<unsigned char, 33> head{};
  in.read(reinterpret_cast<char*>(head.data()), head.size());
  const auto got = static_cast<std::size_t>(in.gcount());
  const auto declared = [&](const char* format, std::uint64_t width, std::uint64_t height) {
    return "the " + std::string(format) + " header declares " + std::to_string(width) + " x " +
           std::to_string(height) + " pixels, more than a file of " + std::to_string(file_size) +
           " bytes can hold (a corrupt or cut file)";
  };
  static const unsigned char kPng[8] = {0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a};
  if (got >= 29 && std::equal(kPng, kPng + 8, head.begin()) && std::equal(head.begin() + 12, head.begin() + 16, "IHDR")) {
    const std::uint64_t width = bigEndian(&head[16], 4), height = bigEndian(&head[20], 4);
    const int bit_depth = head[24], colour = head[25];
    const int channels = colour == 2 ? 3 : colour == 4 ? 2 : colour == 6 ? 4 : 1;  // 0 grey, 3 palette: 1
    // Filtered rows: a filter byte and the row's bits, rounded up to bytes (interlacing adds more).
    const std::uint64_t row = 1 + (width * static_cast<std::uint64_t>(channels * bit_depth) + 7) / 8;
    const std::uint64_t raw = height * row;
    if (raw / 1032 > file_size) return declared("PNG", width, height);
    return "";
  }
  if (got >= 2 && head[0] == 0xff && head[1] == 0xd8) {
    // JPEG: the markers up to the frame header, read as libjpeg reads them (bytes between markers
    // skipped, a segment length below 2 skips only itself), within the first 16 MB.
    std::vector<unsigned char> bytes(static_cast<std::size_t>(std::min<std::uint64_t>(file_size, 16 << 20)));
    in.clear();
    in.seekg(0);
    in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    bytes.resize(static_cast<std::size_t>(in.gcount()));
    std::size_t pos = 2;
    while (pos + 1 < bytes.size()) {
      // libjpeg's next_marker: 0xff, then fill bytes 0xff, then a code that is not 0 (0xff 0x00 is data)
      while (pos < bytes.size() && bytes[pos] != 0xff) ++pos;
      while (pos < bytes.size() && bytes[pos] == 0xff) ++pos;
      if (pos >= bytes.size()) break;
      const int code = bytes[pos++];
      if (code == 0x00 || code == 0x01 || (code >= 0xd0 && code <= 0xd8)) continue;  // data, TEM, RSTn, SOI
      if (code == 0xd9 || code == 0xda || pos + 2 > bytes.size()) break;           // EOI, scan data
      const std::size_t length = bigEndian(&bytes[pos], 2);
      const bool frame = code >= 0xc0 && code <= 0xcf && code != 0xc4 && code != 0xc8 && code != 0xcc;
      if (frame) {
        if (code >= 0xc9 || pos + 7 > bytes.size()) break;  // arithmetic coding: no least bit count per block
        const std::uint64_t height = bigEndian(&bytes[pos + 3], 2), width = bigEndian(&bytes[pos + 5], 2);
        const std::uint64_t blocks = ((width + 7) / 8) * ((height + 7) / 8);
        if (blocks / 8 > file_size) return declared("JPEG", width, height);
        break;
      }
      pos += std::max<std::size_t>(length, 2);
    }
  }
  return "";
}

}  // namespace gasp::detail
