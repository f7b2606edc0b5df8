#include "gasp/rawlog/gz_output_stream.h"

#include <zlib.h>

#include <array>
#include <limits>

#include "gasp/core/error.h"

namespace gasp {

struct GzOutputStream::Deflater {
  z_stream z{};
  std::array<unsigned char, 1 << 16> out{};
  bool open = false;
  ~Deflater() {
    if (open) deflateEnd(&z);
  }
};

GzOutputStream::GzOutputStream(OutputFile& file, int level) : file_(&file) {
  if (level < 0 || level > 9) throw Error("'" + file.path() + "': gzip level must be 0..9 (got " + std::to_string(level) + ")");
  if (level == 0) return;
  deflater_ = std::make_unique<Deflater>();
  // windowBits 15 + 16: a gzip header and trailer, as gzopen() writes.
  if (deflateInit2(&deflater_->z, level, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK)
    throw Error("'" + file.path() + "': cannot start the gzip stream");
  deflater_->open = true;
}

GzOutputStream::~GzOutputStream() = default;

size_t GzOutputStream::Read(void*, size_t) { throw Error("'" + file_->path() + "': an output stream cannot be read"); }

uint64_t GzOutputStream::Seek(int64_t, TSeekOrigin) { throw Error("'" + file_->path() + "': an output stream cannot seek"); }

std::string GzOutputStream::getStreamDescription() const { return "gasp::GzOutputStream '" + file_->path() + "'"; }

size_t GzOutputStream::Write(const void* buffer, size_t count) {
  if (finished_) throw Error("'" + file_->path() + "': written after the end of the stream");
  std::ostream& out = file_->stream();
  if (!deflater_) {
    out.write(static_cast<const char*>(buffer), static_cast<std::streamsize>(count));
  } else {
    z_stream& z = deflater_->z;
    const auto* p = static_cast<const unsigned char*>(buffer);
    size_t left = count;
    while (left > 0) {
      const auto chunk = static_cast<uInt>(std::min<size_t>(left, std::numeric_limits<uInt>::max()));
      z.next_in = const_cast<Bytef*>(p);  // zlib's API is not const-correct
      z.avail_in = chunk;
      do {
        z.next_out = deflater_->out.data();
        z.avail_out = static_cast<uInt>(deflater_->out.size());
        if (deflate(&z, Z_NO_FLUSH) == Z_STREAM_ERROR) throw Error("'" + file_->path() + "': gzip compression failed");
        out.write(reinterpret_cast<const char*>(deflater_->out.data()),
                  static_cast<std::streamsize>(deflater_->out.size() - z.avail_out));
      } while (z.avail_out == 0);
      p += chunk;
      left -= chunk;
    }
  }
  // A failed write is reported here, not only at the end (MRPT stops writing on an exception).
  if (!out) file_->commit();  // throws the system's reason, naming the file
  written_ += count;
  return count;
}

void GzOutputStream::finish() {
  if (finished_) return;
  finished_ = true;
  if (deflater_) {
    z_stream& z = deflater_->z;
    z.next_in = nullptr;
    z.avail_in = 0;
    int rc = Z_OK;
    do {
      z.next_out = deflater_->out.data();
      z.avail_out = static_cast<uInt>(deflater_->out.size());
      rc = deflate(&z, Z_FINISH);
      if (rc == Z_STREAM_ERROR) throw Error("'" + file_->path() + "': gzip compression failed");
      file_->stream().write(reinterpret_cast<const char*>(deflater_->out.data()),
                            static_cast<std::streamsize>(deflater_->out.size() - z.avail_out));
    } while (rc != Z_STREAM_END);
  }
  file_->commit();
}

}  // namespace gasp
