#pragma once
/// \file lookahead_stream.h (private) A read-only mrpt::io::CStream over another one whose next
/// bytes can be looked at before they are read (peek()), so that a rawlog object's size fields
/// can be checked before MRPT deserialises it (object_size_check.h). MRPT's archives read it as
/// they read the file: no seeking.
#include <mrpt/io/CStream.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace gasp::detail {

class LookaheadStream : public mrpt::io::CStream {
 public:
  explicit LookaheadStream(mrpt::io::CStream& source) : source_(source) {}

  size_t Read(void* buffer, size_t count) override {
    auto* out = static_cast<std::uint8_t*>(buffer);
    std::size_t n = std::min(count, ahead_.size() - head_);
    if (n > 0) std::memcpy(out, ahead_.data() + head_, n);
    head_ += n;
    if (head_ == ahead_.size()) ahead_.clear(), head_ = 0;
    if (n < count) n += sourceRead(out + n, count - n);
    position_ += n;
    return n;
  }

  /// Copies up to `count` bytes that start `offset` bytes after the read position into `out`,
  /// without consuming them; returns how many there are (fewer at the end of the stream). The
  /// bytes up to offset + count are buffered: callers check a size against the stream before
  /// looking beyond it (only bytes that exist are ever buffered).
  std::size_t peek(std::uint64_t offset, void* out, std::size_t count) {
    const std::uint64_t need = offset + count;
    if (ahead_.size() - head_ < need) {
      if (head_ > 0) ahead_.erase(ahead_.begin(), ahead_.begin() + static_cast<std::ptrdiff_t>(head_)), head_ = 0;
      while (ahead_.size() < need && !source_end_) {
        const std::size_t want = static_cast<std::size_t>(
            std::clamp<std::uint64_t>(need - ahead_.size(), 1 << 16, 1 << 20));  // chunks: never more than exists
        const std::size_t old = ahead_.size();
        ahead_.resize(old + want);
        const std::size_t got = sourceRead(ahead_.data() + old, want);
        ahead_.resize(old + got);
        if (got == 0) source_end_ = true;
      }
    }
    const std::uint64_t available = ahead_.size() - head_;
    if (offset >= available) return 0;
    const std::size_t n = static_cast<std::size_t>(std::min<std::uint64_t>(count, available - offset));
    std::memcpy(out, ahead_.data() + head_ + offset, n);
    return n;
  }

  size_t Write(const void*, size_t) override { throw std::runtime_error("LookaheadStream is read-only"); }
  uint64_t Seek(int64_t, CStream::TSeekOrigin) override { throw std::runtime_error("LookaheadStream cannot seek"); }
  uint64_t getTotalBytesCount() const override { return source_.getTotalBytesCount(); }
  uint64_t getPosition() const override { return position_; }  ///< bytes read (of the content)

 private:
  /// source_.Read(), whose "-1" (CFileGZInputStream at a damaged gzip stream: gzread's error,
  /// as size_t) reads nothing: the content ends there, as for MRPT.
  std::size_t sourceRead(void* buffer, std::size_t count) {
    const std::size_t got = source_.Read(buffer, count);
    return got > count ? 0 : got;
  }

  mrpt::io::CStream& source_;
  std::vector<std::uint8_t> ahead_;  ///< bytes taken from source_ and not yet read, from head_
  std::size_t head_ = 0;
  std::uint64_t position_ = 0;
  bool source_end_ = false;
};

}  // namespace gasp::detail
