#pragma once
/// \file gzip_content.h (private) A file's content read to its end through zlib: its length and
/// first bytes, with a damaged or cut gzip stream as an error (MRPT's CFileGZInputStream reports
/// those as the end of the file). gzread reads plain files as they are.
#include <zlib.h>

#include <array>
#include <cstdint>
#include <string>

#include "gasp/core/error.h"

namespace gasp::detail {

struct GzipContent {
  std::uint64_t length = 0;  ///< bytes of content (uncompressed)
  std::string head;          ///< its first bytes (as many as asked for, fewer in a shorter file)
};

/// Throws gasp::Error "<what> '<path>': corrupt or truncated gzip stream: ..." or "cannot open".
inline GzipContent readGzipContent(const std::string& path, const std::string& what, std::size_t head_bytes = 0) {
  gzFile f = gzopen(path.c_str(), "rb");
  if (!f) throw Error(what + " '" + path + "': cannot open the file");
  std::array<char, 1 << 16> buffer{};
  GzipContent content;
  int n = 0;
  while ((n = gzread(f, buffer.data(), static_cast<unsigned>(buffer.size()))) > 0) {
    if (content.head.size() < head_bytes)
      content.head.append(buffer.data(), std::min<std::size_t>(static_cast<std::size_t>(n), head_bytes - content.head.size()));
    content.length += static_cast<std::uint64_t>(n);
  }
  int code = Z_OK;
  const std::string message = gzerror(f, &code);  // zlib also ends a read quietly at a cut trailer
  const int closed = gzclose(f);                  // ... and reports a bad checksum here
  if (n < 0 || code != Z_OK || closed != Z_OK)
    throw Error(what + " '" + path + "': corrupt or truncated gzip stream" +
                (message.empty() || code == Z_OK ? std::string(" (checksum or trailer)") : ": " + message));
  return content;
}

}  // namespace gasp::detail
