#pragma once
/// \file content_scan.h (private) A rawlog's content read once through zlib (plain files as they
/// are): its length, and the error a damaged or cut gzip stream gives, kept for later instead of
/// thrown. RawlogObjects scans at open, checks each object's sizes against the bytes that remain
/// (object_size_check.h), and reports the damage where MRPT's stream ends early, after the
/// objects before it were read. The length counts every byte zlib can inflate before the damage
/// (inflate, not gzread, which drops the buffer in which it meets the damage).
#include <zlib.h>

#include <array>
#include <cstdint>
#include <cstdio>
#include <string>

namespace gasp::detail {

struct ContentScan {
  std::uint64_t length = 0;  ///< bytes of content that can be read (up to the damage, if any)
  std::string error;         ///< "" or "corrupt or truncated gzip stream..."
};

inline ContentScan scanContent(const std::string& path) {
  ContentScan scan;
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) {
    scan.error = "cannot open the file";
    return scan;
  }
  std::array<unsigned char, 1 << 16> in{}, out{};
  std::size_t n = std::fread(in.data(), 1, in.size(), f);
  if (n < 2 || in[0] != 0x1f || in[1] != 0x8b) {  // plain: the file as it is (as gzread reads it)
    while (n > 0) scan.length += n, n = std::fread(in.data(), 1, in.size(), f);
    std::fclose(f);
    return scan;
  }
  z_stream z{};
  inflateInit2(&z, 16 + MAX_WBITS);
  z.next_in = in.data();
  z.avail_in = static_cast<uInt>(n);
  int code = Z_OK;
  for (;;) {
    if (z.avail_in == 0) {
      n = std::fread(in.data(), 1, in.size(), f);
      if (n == 0) break;
      z.next_in = in.data();
      z.avail_in = static_cast<uInt>(n);
    }
    z.next_out = out.data();
    z.avail_out = static_cast<uInt>(out.size());
    code = inflate(&z, Z_NO_FLUSH);
    scan.length += out.size() - z.avail_out;
    if (code == Z_STREAM_END) {  // another gzip member may follow (gzread reads them all)
      if (z.avail_in == 0) {
        n = std::fread(in.data(), 1, in.size(), f);
        if (n == 0) break;
        z.next_in = in.data();
        z.avail_in = static_cast<uInt>(n);
      }
      if (z.avail_in < 2 || z.next_in[0] != 0x1f || z.next_in[1] != 0x8b) break;  // trailing bytes: ignored
      inflateReset(&z);
      code = Z_OK;
      continue;
    }
    if (code != Z_OK) break;
  }
  if (code != Z_STREAM_END)
    scan.error = std::string("corrupt or truncated gzip stream") +
                 (code == Z_OK || code == Z_BUF_ERROR ? " (cut short)" : z.msg ? std::string(": ") + z.msg : "");
  inflateEnd(&z);
  std::fclose(f);
  return scan;
}

}  // namespace gasp::detail
