#include "gasp/pipeline/view_bytes.h"

#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

#include "gasp/core/error.h"

namespace gasp {

namespace {

// "GVW1", then a byte-order probe: the reader refuses another byte order or float format.
constexpr char kMagic[4] = {'G', 'V', 'W', '1'};
constexpr std::uint32_t kProbe = 0x01020304u;
constexpr double kDoubleProbe = 1.5;

class Writer {
 public:
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    out_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void putSize(std::size_t n) { put(static_cast<std::uint64_t>(n)); }
  void putString(const std::string& s) {
    putSize(s.size());
    out_ += s;
  }
  template <class T>
  void putVector(const std::vector<T>& v) {
    putSize(v.size());
    for (const T& x : v) put(x);
  }
  /// A matrix's type, size and elements (row by row).
  void putMat(const cv::Mat& m) {
    put(static_cast<std::int32_t>(m.empty() ? -1 : m.type()));
    if (m.empty()) return;
    put(static_cast<std::int32_t>(m.rows));
    put(static_cast<std::int32_t>(m.cols));
    const std::size_t row_bytes = static_cast<std::size_t>(m.cols) * m.elemSize();
    for (int r = 0; r < m.rows; ++r) out_.append(reinterpret_cast<const char*>(m.ptr(r)), row_bytes);
  }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

class Reader {
 public:
  explicit Reader(std::string_view in) : in_(in) {}
  template <class T>
  T get(const char* what) {
    static_assert(std::is_trivially_copyable_v<T>);
    need(sizeof(T), what);
    T v;
    std::memcpy(&v, in_.data() + at_, sizeof v);
    at_ += sizeof v;
    return v;
  }
  /// A count of items of `item_bytes` each, at most what is left.
  std::size_t getSize(std::size_t item_bytes, const char* what) {
    const std::uint64_t n = get<std::uint64_t>(what);
    if (item_bytes > 0 && n > (in_.size() - at_) / item_bytes) fail(std::string(what) + ": a count past the bytes' end");
    return static_cast<std::size_t>(n);
  }
  std::string getString(const char* what) {
    const std::size_t n = getSize(1, what);
    std::string s(in_.substr(at_, n));
    at_ += n;
    return s;
  }
  template <class T>
  std::vector<T> getVector(const char* what) {
    std::vector<T> v(getSize(sizeof(T), what));
    for (T& x : v) x = get<T>(what);
    return v;
  }
  cv::Mat getMat(const char* what, int expected_type) {
    const auto type = get<std::int32_t>(what);
    if (type == -1) return {};
    if (type != expected_type) fail(std::string(what) + ": another element type");
    const auto rows = get<std::int32_t>(what), cols = get<std::int32_t>(what);
    if (rows < 1 || cols < 1 || rows > kMaxImageSide || cols > kMaxImageSide)
      fail(std::string(what) + ": a size out of range");
    const std::size_t row_bytes = static_cast<std::size_t>(cols) * CV_ELEM_SIZE(type);
    need(row_bytes * static_cast<std::size_t>(rows), what);  // before allocating: the bytes hold them all
    cv::Mat m(rows, cols, type);
    for (int r = 0; r < rows; ++r, at_ += row_bytes) std::memcpy(m.ptr(r), in_.data() + at_, row_bytes);
    return m;
  }
  bool atEnd() const { return at_ == in_.size(); }
  [[noreturn]] static void fail(const std::string& why) { throw Error("view bytes: " + why); }

 private:
  void need(std::size_t n, const char* what) const {
    if (n > in_.size() - at_) fail(std::string("truncated at ") + what);
  }
  std::string_view in_;
  std::size_t at_ = 0;
};

void putVec(Writer& w, const Eigen::Vector3d& v) {
  for (int i = 0; i < 3; ++i) w.put(v(i));
}
Eigen::Vector3d getVec(Reader& r, const char* what) {
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) v(i) = r.get<double>(what);
  return v;
}

void putScan(Writer& w, const RangeScan& s) {
  w.put(s.timestamp);
  w.putString(s.model);
  w.putMat(s.range_m);
  w.putVector(s.elevation_rad);
  w.putVector(s.azimuth_rad);
  w.putVector(s.laser_of_row);
  w.putMat(s.ray);
  w.put(s.sweep_duration_s);
  for (int i = 0; i < 16; ++i) w.put(s.T_robot_sensor.matrix()(i / 4, i % 4));
}

RangeScan getScan(Reader& r) {
  RangeScan s;
  s.timestamp = r.get<double>("the sweep's timestamp");
  s.model = r.getString("the sweep's model");
  s.range_m = r.getMat("the sweep's ranges", CV_32FC1);
  s.elevation_rad = r.getVector<double>("the sweep's elevations");
  s.azimuth_rad = r.getVector<double>("the sweep's azimuths");
  s.laser_of_row = r.getVector<int>("the sweep's laser ids");
  s.ray = r.getMat("the sweep's rays", CV_32FC3);
  s.sweep_duration_s = r.get<double>("the sweep's duration");
  Eigen::Matrix4d M;
  for (int i = 0; i < 16; ++i) M(i / 4, i % 4) = r.get<double>("the sweep's mounting");
  s.T_robot_sensor.matrix() = M;
  return s;
}

}  // namespace

std::string viewBytes(const DepthView& view) {
  Writer w;
  for (const char c : kMagic) w.put(c);
  w.put(kProbe);
  w.put(kDoubleProbe);
  w.putMat(view.depth_m);
  w.put(static_cast<std::uint8_t>(view.projection.isPinhole() ? 0 : 1));
  if (view.projection.isPinhole()) {
    const CameraIntrinsics& k = view.projection.pinhole();
    w.put(static_cast<std::int32_t>(k.width));
    w.put(static_cast<std::int32_t>(k.height));
    for (const double d : {k.fx, k.fy, k.cx, k.cy}) w.put(d);
    for (const double d : k.distortion) w.put(d);
  } else {
    const SphericalGrid& g = view.projection.grid();
    w.putVector(g.elevation_rad);
    w.put(g.azimuth_first_rad);
    w.put(g.azimuth_step_rad);
    w.put(static_cast<std::int32_t>(g.columns));
    w.putMat(g.ray);
  }
  const SuperpixelSegmentation& seg = view.segmentation;
  w.putMat(seg.labels);
  w.putSize(seg.patches.size());
  for (const SurfacePatch& p : seg.patches) {
    w.put(static_cast<std::int32_t>(p.id));
    putVec(w, p.centroid);
    putVec(w, p.normal);
    w.put(p.area_m2);
    w.put(static_cast<std::int32_t>(p.pixel_count));
    for (int i = 0; i < 9; ++i) w.put(p.covariance(i / 3, i % 3));
    w.put(p.planarity);
    for (const int b : {p.bbox.x, p.bbox.y, p.bbox.width, p.bbox.height}) w.put(static_cast<std::int32_t>(b));
  }
  w.putSize(seg.adjacency.size());
  for (const auto& list : seg.adjacency) w.putVector(list);
  w.putSize(seg.stats.valid_pixels);
  w.putSize(seg.stats.assigned_pixels);
  w.putSize(seg.stats.dropped_pixels);
  w.put(static_cast<std::uint8_t>(view.returns ? 1 : 0));
  if (view.returns) putScan(w, view.returns->scan());
  return w.take();
}

DepthView viewFromBytes(std::string_view bytes, const SuperpixelParams& superpixels, const ReturnsRefineParams& returns) {
  Reader r(bytes);
  for (const char c : kMagic)
    if (r.get<char>("the header") != c) Reader::fail("not a view's bytes (no GVW1 header)");
  if (r.get<std::uint32_t>("the header") != kProbe || r.get<double>("the header") != kDoubleProbe)
    Reader::fail("written on a machine of another byte order or number format");
  DepthView v;
  v.depth_m = r.getMat("the depth", CV_32FC1);
  const auto kind = r.get<std::uint8_t>("the projection");
  if (kind == 0) {
    CameraIntrinsics k;
    k.width = r.get<std::int32_t>("the intrinsics");
    k.height = r.get<std::int32_t>("the intrinsics");
    k.fx = r.get<double>("the intrinsics");
    k.fy = r.get<double>("the intrinsics");
    k.cx = r.get<double>("the intrinsics");
    k.cy = r.get<double>("the intrinsics");
    for (double& d : k.distortion) d = r.get<double>("the intrinsics");
    k.validate();
    v.projection = ViewProjection(k);
  } else if (kind == 1) {
    SphericalGrid g;
    g.elevation_rad = r.getVector<double>("the grid's elevations");
    g.azimuth_first_rad = r.get<double>("the grid");
    g.azimuth_step_rad = r.get<double>("the grid");
    g.columns = r.get<std::int32_t>("the grid");
    g.ray = r.getMat("the grid's rays", CV_32FC3);
    v.projection = ViewProjection::spherical(std::move(g));  // validates it
  } else {
    Reader::fail("an unknown projection");
  }
  if (!v.depth_m.empty() && (v.depth_m.cols != v.projection.width() || v.depth_m.rows != v.projection.height()))
    Reader::fail("the depth image's size is not the projection's");
  SuperpixelSegmentation& seg = v.segmentation;
  seg.labels = r.getMat("the labels", CV_32SC1);
  const std::size_t n = r.getSize(4 + 3 * 8 + 3 * 8 + 8 + 4 + 9 * 8 + 8 + 4 * 4, "the patches");
  seg.patches.resize(n);
  for (SurfacePatch& p : seg.patches) {
    p.id = r.get<std::int32_t>("a patch");
    p.centroid = getVec(r, "a patch");
    p.normal = getVec(r, "a patch");
    p.area_m2 = r.get<double>("a patch");
    p.pixel_count = r.get<std::int32_t>("a patch");
    for (int i = 0; i < 9; ++i) p.covariance(i / 3, i % 3) = r.get<double>("a patch");
    p.planarity = r.get<double>("a patch");
    p.bbox.x = r.get<std::int32_t>("a patch");
    p.bbox.y = r.get<std::int32_t>("a patch");
    p.bbox.width = r.get<std::int32_t>("a patch");
    p.bbox.height = r.get<std::int32_t>("a patch");
  }
  seg.adjacency.resize(r.getSize(8, "the adjacency"));
  for (auto& list : seg.adjacency) {
    list = r.getVector<int>("the adjacency");
    for (const int j : list)
      if (j < 0 || static_cast<std::size_t>(j) >= n) Reader::fail("the adjacency names no patch");
  }
  seg.stats.valid_pixels = r.getSize(0, "the counts");
  seg.stats.assigned_pixels = r.getSize(0, "the counts");
  seg.stats.dropped_pixels = r.getSize(0, "the counts");
  if (seg.labels.empty() && n > 0) Reader::fail("patches without labels");
  if (!seg.labels.empty()) {
    if (seg.labels.size() != v.depth_m.size()) Reader::fail("the labels' size is not the depth image's");
    for (int row = 0; row < seg.labels.rows; ++row)
      for (int col = 0; col < seg.labels.cols; ++col)
        if (const int l = seg.labels.at<int>(row, col); l < -1 || (l >= 0 && static_cast<std::size_t>(l) >= n))
          Reader::fail("a label names no patch");
  }
  const auto has_returns = r.get<std::uint8_t>("the sweep");
  if (has_returns > 1) Reader::fail("the sweep's flag is neither 0 nor 1");
  if (has_returns == 1) v.returns = std::make_shared<const SweepReturns>(getScan(r), returns);  // validates the scan
  if (!r.atEnd()) Reader::fail("bytes past the view's end");
  v.superpixels = superpixels;
  return v;
}

}  // namespace gasp
