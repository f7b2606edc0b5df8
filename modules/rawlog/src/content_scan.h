#pragma once
/// \file content_scan.h (private) A rawlog's content read once through zlib (plain files as they
/// are): its length, and the error a damaged or cut gzip stream gives, kept for later instead of
/// thrown. RawlogObjects scans at open, checks each object's sizes against the bytes that remain
/// (object_size_check.h), and reports the damage where MRPT's stream ends early, after the
/// objects before it were read.
#include <zlib.h>

#include <array>
#include <cstdint>
#include <string>

namespace gasp::detail {

struct ContentScan {
  std::uint64_t length = 0;  ///< bytes of content that can be read (up to the damage, if any)
  std::string error;         ///< "" or "corrupt or truncated gzip stream..." (as readGzipContent)
};

inline ContentScan scanContent(const std::string& path) {
  ContentScan scan;
  gzFile f = gzopen(path.c_str(), "rb");
  if (!f) {
    scan.error = "cannot open the file";
    return scan;
  }
  std::array<char, 1 << 16> buffer{};
  int n = 0;
  while ((n = gzread(f, buffer.data(), static_cast<unsigned>(buffer.size()))) > 0)
    scan.length += static_cast<std::uint64_t>(n);
  int code = Z_OK;
  const std::string message = gzerror(f, &code);  // zlib also ends a read quietly at a cut trailer
  const int closed = gzclose(f);                  // ... and reports a bad checksum here
  if (n < 0 || code != Z_OK || closed != Z_OK)
    scan.error = "corrupt or truncated gzip stream" +
                 (message.empty() || code == Z_OK ? std::string(" (checksum or trailer)") : ": " + message);
  return scan;
}

}  // namespace gasp::detail
