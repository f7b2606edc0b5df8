#pragma once
/// \file gz_output_stream.h An MRPT output stream into an OutputFile, gzip-compressed or plain,
/// so that rawlogs, simple maps and 3D scenes are written whole or not at all
/// (gasp/core/output_file.h) like every other output.
#include <mrpt/io/CStream.h>

#include <cstdint>
#include <memory>

#include "gasp/core/output_file.h"

namespace gasp {

class GzOutputStream : public mrpt::io::CStream {
 public:
  /// Writes into `file` (which must outlive this stream): gzip at `level` 1..9 (what MRPT's
  /// CFileGZOutputStream writes), or the bytes as they are for level 0.
  GzOutputStream(OutputFile& file, int level);
  ~GzOutputStream() override;

  size_t Read(void* buffer, size_t count) override;  ///< throws: an output stream
  size_t Write(const void* buffer, size_t count) override;
  uint64_t Seek(int64_t offset, TSeekOrigin origin = sFromBeginning) override;  ///< throws
  uint64_t getTotalBytesCount() const override { return written_; }
  uint64_t getPosition() const override { return written_; }
  std::string getStreamDescription() const override;

  /// Ends the gzip stream and commits the file (OutputFile::commit()); throws gasp::Error naming
  /// the file. Without it the file is discarded with the OutputFile.
  void finish();

 private:
  struct Deflater;
  OutputFile* file_;
  std::unique_ptr<Deflater> deflater_;  ///< null for level 0
  uint64_t written_ = 0;                ///< uncompressed bytes
  bool finished_ = false;
};

}  // namespace gasp
