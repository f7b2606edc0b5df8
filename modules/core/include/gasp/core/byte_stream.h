#pragma once
/// \file byte_stream.h Plain values as bytes and back, exactly, for handing GASP's records to
/// another process of the same job (view_bytes.h, tracked_frame.h, the MPI messages).
///
/// Numbers are written as the machine holds them (little-endian IEEE doubles and floats on every
/// platform GASP builds on); a format that crosses processes starts with writeHeader(), which the
/// reader checks, so that bytes of another byte order or number format are refused. Reading never
/// trusts a count: every size is checked against the bytes left before anything is allocated, and
/// each error names what was being read.
#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "gasp/core/camera_intrinsics.h"
#include "gasp/core/pose.h"
#include "gasp/core/range_scan.h"

namespace gasp {

class ByteWriter {
 public:
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    out_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void putSize(std::size_t n) { put(static_cast<std::uint64_t>(n)); }
  void putFlag(bool b) { put(static_cast<std::uint8_t>(b ? 1 : 0)); }
  void putString(std::string_view s) {
    putSize(s.size());
    out_ += s;
  }
  template <class T>
  void putVector(const std::vector<T>& v) {
    putSize(v.size());
    for (const T& x : v) put(x);
  }
  /// A fixed-size Eigen matrix's elements, row by row.
  template <class Derived>
  void putMatrix(const Eigen::MatrixBase<Derived>& m) {
    for (Eigen::Index r = 0; r < m.rows(); ++r)
      for (Eigen::Index c = 0; c < m.cols(); ++c) put(static_cast<double>(m(r, c)));
  }
  void putPose(const Isometry3& T) { putMatrix(T.matrix()); }
  /// A matrix's type, size and elements (row by row); empty: the type -1 alone.
  void putMat(const cv::Mat& m);
  void putIntrinsics(const CameraIntrinsics& k);
  void putScan(const RangeScan& s);
  /// Four magic characters naming the format, then the byte-order and number-format probes.
  void writeHeader(const char (&magic)[5]);
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

class ByteReader {
 public:
  /// `format`: what the bytes are, the start of every error's message ("view bytes").
  ByteReader(std::string_view in, std::string format) : in_(in), format_(std::move(format)) {}
  template <class T>
  T get(const char* what) {
    static_assert(std::is_trivially_copyable_v<T>);
    need(sizeof(T), what);
    T v;
    std::memcpy(&v, in_.data() + at_, sizeof v);
    at_ += sizeof v;
    return v;
  }
  /// A byte that must be 0 or 1 (ByteWriter::putFlag()).
  bool getFlag(const char* what);
  /// A count of items of `item_bytes` each, at most what is left.
  std::size_t getSize(std::size_t item_bytes, const char* what);
  std::string getString(const char* what);
  template <class T>
  std::vector<T> getVector(const char* what) {
    std::vector<T> v(getSize(sizeof(T), what));
    for (T& x : v) x = get<T>(what);
    return v;
  }
  template <class Matrix>
  Matrix getMatrix(const char* what) {
    Matrix m;
    for (Eigen::Index r = 0; r < m.rows(); ++r)
      for (Eigen::Index c = 0; c < m.cols(); ++c) m(r, c) = get<double>(what);
    return m;
  }
  /// A rigid pose's 4x4 matrix (its last row checked).
  Isometry3 getPose(const char* what);
  /// A matrix of `expected_type` (or empty), each side 1 to kMaxImageSide.
  cv::Mat getMat(const char* what, int expected_type);
  CameraIntrinsics getIntrinsics(const char* what);  ///< validated
  RangeScan getScan();                               ///< not validated: its users do
  /// Refuses bytes without the header `magic` or of another byte order or number format.
  void readHeader(const char (&magic)[5]);
  bool atEnd() const { return at_ == in_.size(); }
  /// Throws gasp::Error unless every byte was read.
  void expectEnd() const;
  /// Throws gasp::Error: "<format>: <why>".
  [[noreturn]] void fail(const std::string& why) const;

 private:
  void need(std::size_t n, const char* what) const;
  std::string_view in_;
  std::size_t at_ = 0;
  std::string format_;
};

}  // namespace gasp
