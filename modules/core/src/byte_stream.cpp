#include "gasp/core/byte_stream.h"

#include "gasp/core/error.h"

namespace gasp {

namespace {
constexpr std::uint32_t kProbe = 0x01020304u;
constexpr double kDoubleProbe = 1.5;
}  // namespace

void ByteWriter::putMat(const cv::Mat& m) {
  put(static_cast<std::int32_t>(m.empty() ? -1 : m.type()));
  if (m.empty()) return;
  put(static_cast<std::int32_t>(m.rows));
  put(static_cast<std::int32_t>(m.cols));
  const std::size_t row_bytes = static_cast<std::size_t>(m.cols) * m.elemSize();
  for (int r = 0; r < m.rows; ++r) out_.append(reinterpret_cast<const char*>(m.ptr(r)), row_bytes);
}

void ByteWriter::putIntrinsics(const CameraIntrinsics& k) {
  put(static_cast<std::int32_t>(k.width));
  put(static_cast<std::int32_t>(k.height));
  for (const double d : {k.fx, k.fy, k.cx, k.cy}) put(d);
  for (const double d : k.distortion) put(d);
}

void ByteWriter::putScan(const RangeScan& s) {
  put(s.timestamp);
  putString(s.model);
  putMat(s.range_m);
  putVector(s.elevation_rad);
  putVector(s.azimuth_rad);
  putVector(s.laser_of_row);
  putMat(s.ray);
  put(s.sweep_duration_s);
  putPose(s.T_robot_sensor);
}

void ByteWriter::writeHeader(const char (&magic)[5]) {
  out_.append(magic, 4);
  put(kProbe);
  put(kDoubleProbe);
}

bool ByteReader::getFlag(const char* what) {
  const auto b = get<std::uint8_t>(what);
  if (b > 1) fail(std::string(what) + ": a flag neither 0 nor 1");
  return b == 1;
}

std::size_t ByteReader::getSize(std::size_t item_bytes, const char* what) {
  const std::uint64_t n = get<std::uint64_t>(what);
  if (item_bytes > 0 && n > (in_.size() - at_) / item_bytes) fail(std::string(what) + ": a count past the bytes' end");
  return static_cast<std::size_t>(n);
}

std::string ByteReader::getString(const char* what) {
  const std::size_t n = getSize(1, what);
  std::string s(in_.substr(at_, n));
  at_ += n;
  return s;
}

Isometry3 ByteReader::getPose(const char* what) {
  const Eigen::Matrix4d M = getMatrix<Eigen::Matrix4d>(what);
  if (M.row(3) != Eigen::RowVector4d(0, 0, 0, 1)) fail(std::string(what) + ": not a rigid pose's matrix");
  Isometry3 T;
  T.matrix() = M;
  return T;
}

cv::Mat ByteReader::getMat(const char* what, int expected_type) {
  const auto type = get<std::int32_t>(what);
  if (type == -1) return {};
  if (type != expected_type) fail(std::string(what) + ": another element type");
  const auto rows = get<std::int32_t>(what), cols = get<std::int32_t>(what);
  if (rows < 1 || cols < 1 || rows > kMaxImageSide || cols > kMaxImageSide) fail(std::string(what) + ": a size out of range");
  const std::size_t row_bytes = static_cast<std::size_t>(cols) * CV_ELEM_SIZE(type);
  need(row_bytes * static_cast<std::size_t>(rows), what);  // before allocating: the bytes hold them all
  cv::Mat m(rows, cols, type);
  for (int r = 0; r < rows; ++r, at_ += row_bytes) std::memcpy(m.ptr(r), in_.data() + at_, row_bytes);
  return m;
}

CameraIntrinsics ByteReader::getIntrinsics(const char* what) {
  CameraIntrinsics k;
  k.width = get<std::int32_t>(what);
  k.height = get<std::int32_t>(what);
  k.fx = get<double>(what);
  k.fy = get<double>(what);
  k.cx = get<double>(what);
  k.cy = get<double>(what);
  for (double& d : k.distortion) d = get<double>(what);
  try {
    k.validate();
  } catch (const Error& e) {
    fail(std::string(what) + ": " + e.what());
  }
  return k;
}

RangeScan ByteReader::getScan() {
  RangeScan s;
  s.timestamp = get<double>("the sweep's timestamp");
  s.model = getString("the sweep's model");
  s.range_m = getMat("the sweep's ranges", CV_32FC1);
  s.elevation_rad = getVector<double>("the sweep's elevations");
  s.azimuth_rad = getVector<double>("the sweep's azimuths");
  s.laser_of_row = getVector<int>("the sweep's laser ids");
  s.ray = getMat("the sweep's rays", CV_32FC3);
  s.sweep_duration_s = get<double>("the sweep's duration");
  s.T_robot_sensor = getPose("the sweep's mounting");
  return s;
}

void ByteReader::readHeader(const char (&magic)[5]) {
  for (int i = 0; i < 4; ++i)
    if (get<char>("the header") != magic[i]) fail(std::string("no ") + magic + " header");
  if (get<std::uint32_t>("the header") != kProbe || get<double>("the header") != kDoubleProbe)
    fail("written on a machine of another byte order or number format");
}

void ByteReader::expectEnd() const {
  if (!atEnd()) fail("bytes past the end");
}

void ByteReader::fail(const std::string& why) const { throw Error(format_ + ": " + why); }

void ByteReader::need(std::size_t n, const char* what) const {
  if (n > in_.size() - at_) fail(std::string("truncated at ") + what);
}

}  // namespace gasp
