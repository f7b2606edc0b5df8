// CSuperpixelMap's versioned serialization. Version 3: version 2's, a sweep's normal settings
// ending with the range noise its normals' windows grew against (ReturnsRefineParams::
// normal_noise_m) and the plane tolerance they were checked with (the last gate); a version 2
// sweep is read with adjacent-row windows, as it was made, and the default last gate.
// Version 2: version 1's, each view led by its kind
// (uint8): 0 a depth image's view as version 1 writes it (then its segmentation parameters); 1 a
// LiDAR sweep's: timestamp, sensor label, T_map_camera (3x4), the sweep (model, timestamp, sweep
// duration, rows, columns, elevations, azimuths, laser ids, ranges [m], the ray table or none),
// its segmentation parameters (ini text) and the returns' normal settings. A sweep's view is made
// again from these on reading (binning, segmentation and normals are deterministic).
// Version 1:
//   genericMapParams; creation, likelihood and render options as ini text (every parameter,
//   params_io.h); view count; per view: timestamp, sensor label, T_map_camera (3x4), depth
//   intrinsics, depth image (float [m]), label image (run-length coded), patches, adjacency, pixel
//   counts, patch colours, then the segmentation parameters the view was made with (ini text).
// Version 0 (read only) had no per-view parameters (the views take the creation options) and
// fewer option keys (the others keep their defaults).
// Reading checks every size and range and the view's consistency, so a corrupt stream gives an
// exception naming the problem and leaves the map unchanged.
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/core/exceptions.h>
#include <mrpt/serialization/CArchive.h>

#include <cstdint>

#include "gasp/core/error.h"
#include "gasp/mrpt/CSuperpixelMap.h"
#include "gasp/pipeline/range_view.h"

namespace gasp {

namespace {

constexpr std::uint32_t kMaxImageSide = 16384;
constexpr std::uint64_t kMaxImagePixels = 4096ull * 4096ull;
// A stored sweep: 256 lasers, a column every 0.01 deg (a view is made again from it on reading).
constexpr int kMaxSweepRows = 256;
constexpr int kMaxSweepColumns = 36000;

template <class Options>
std::string optionsText(const Options& o) {
  mrpt::config::CConfigFileMemory mem;
  o.saveToConfigFile(mem, "options");
  return mem.getContent();
}

template <class Options>
void optionsFromText(const std::string& text, Options& o) {
  const mrpt::config::CConfigFileMemory mem(text);
  o.loadFromConfigFile(mem, "options");
}

void writeVec(mrpt::serialization::CArchive& out, const Eigen::Vector3d& v) { out << v.x() << v.y() << v.z(); }
Eigen::Vector3d readVec(mrpt::serialization::CArchive& in) {
  double x, y, z;
  in >> x >> y >> z;
  return {x, y, z};
}

void readExactly(mrpt::serialization::CArchive& in, float* data, std::size_t n, const char* what) {
  if (n == 0) return;
  if (in.ReadBufferFixEndianness(data, n) != n * sizeof(float)) THROW_EXCEPTION_FMT("truncated %s", what);
}

void writePose(mrpt::serialization::CArchive& out, const Isometry3& T) {
  const Eigen::Matrix<double, 3, 4> M = T.matrix().topRows<3>();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) out << M(r, c);
}

Isometry3 readPose(mrpt::serialization::CArchive& in) {
  Eigen::Matrix4d M = Eigen::Matrix4d::Identity();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) in >> M(r, c);
  Isometry3 T = Isometry3::Identity();
  T.matrix() = M;
  return T;
}

void writeView(mrpt::serialization::CArchive& out, const SuperpixelMapView& v) {
  out << v.timestamp << v.sensor_label;
  writePose(out, v.T_map_camera);
  const CameraIntrinsics& k = v.view.projection.pinhole();
  out << static_cast<std::int32_t>(k.width) << static_cast<std::int32_t>(k.height) << k.fx << k.fy << k.cx << k.cy;
  for (double d : k.distortion) out << d;
  // Depth [m], row-major.
  const cv::Mat depth = v.view.depth_m.isContinuous() ? v.view.depth_m : v.view.depth_m.clone();
  out.WriteBufferFixEndianness(depth.ptr<float>(0), depth.total());
  // Labels, run-length coded in row-major order.
  const SuperpixelSegmentation& seg = v.view.segmentation;
  std::vector<std::pair<std::int32_t, std::uint32_t>> runs;
  for (int r = 0; r < seg.labels.rows; ++r) {
    const int* l = seg.labels.ptr<int>(r);
    for (int c = 0; c < seg.labels.cols; ++c) {
      if (!runs.empty() && runs.back().first == l[c])
        ++runs.back().second;
      else
        runs.emplace_back(l[c], 1u);
    }
  }
  out << static_cast<std::uint32_t>(runs.size());
  for (const auto& [label, length] : runs) out << label << length;
  out << static_cast<std::uint32_t>(seg.patches.size());
  for (const SurfacePatch& p : seg.patches) {
    out << static_cast<std::int32_t>(p.id);
    writeVec(out, p.centroid);
    writeVec(out, p.normal);
    out << p.area_m2 << static_cast<std::int32_t>(p.pixel_count);
    for (int i = 0; i < 9; ++i) out << p.covariance(i / 3, i % 3);
    out << p.planarity << static_cast<std::int32_t>(p.bbox.x) << static_cast<std::int32_t>(p.bbox.y)
        << static_cast<std::int32_t>(p.bbox.width) << static_cast<std::int32_t>(p.bbox.height);
  }
  for (const auto& list : seg.adjacency) {
    out << static_cast<std::uint32_t>(list.size());
    for (int j : list) out << static_cast<std::int32_t>(j);
  }
  out << static_cast<std::uint64_t>(seg.stats.valid_pixels) << static_cast<std::uint64_t>(seg.stats.assigned_pixels)
      << static_cast<std::uint64_t>(seg.stats.dropped_pixels);
  out << static_cast<std::uint32_t>(v.patch_rgb.size());
  for (const Rgb8& c : v.patch_rgb) out << c[0] << c[1] << c[2];
}

/// A sweep's view: what makes it again (the view's segmentation parameters are written after it).
void writeSweepView(mrpt::serialization::CArchive& out, const SuperpixelMapView& v) {
  out << v.timestamp << v.sensor_label;
  writePose(out, v.T_map_camera);
  const RangeScan& s = v.view.returns->scan();
  out << s.model << s.timestamp << s.sweep_duration_s;
  writePose(out, s.T_robot_sensor);
  const int rows = s.range_m.rows, cols = s.range_m.cols;
  out << static_cast<std::int32_t>(rows) << static_cast<std::int32_t>(cols);
  for (double e : s.elevation_rad) out << e;
  for (double a : s.azimuth_rad) out << a;
  out << static_cast<std::uint32_t>(s.laser_of_row.size());  // 0 or one per row
  for (int l : s.laser_of_row) out << static_cast<std::int32_t>(l);
  const cv::Mat range = s.range_m.isContinuous() ? s.range_m : s.range_m.clone();
  out.WriteBufferFixEndianness(range.ptr<float>(0), range.total());
  out << static_cast<std::uint8_t>(s.ray.empty() ? 0 : 1);
  if (!s.ray.empty()) {
    const cv::Mat ray = s.ray.isContinuous() ? s.ray : s.ray.clone();
    out.WriteBufferFixEndianness(ray.ptr<float>(0), ray.total() * 3);
  }
}

/// The sweep and view fields of writeSweepView(); the caller makes the view.
SuperpixelMapView readSweepView(mrpt::serialization::CArchive& in, RangeScan& s) {
  SuperpixelMapView v;
  in >> v.timestamp >> v.sensor_label;
  v.T_map_camera = readPose(in);
  in >> s.model >> s.timestamp >> s.sweep_duration_s;
  s.T_robot_sensor = readPose(in);
  std::int32_t rows, cols;
  in >> rows >> cols;
  if (rows < 1 || cols < 2 || rows > kMaxSweepRows || cols > kMaxSweepColumns)
    THROW_EXCEPTION_FMT("sweep size %d rows x %d columns out of range (at most %d x %d)", rows, cols, kMaxSweepRows,
                        kMaxSweepColumns);
  s.elevation_rad.resize(static_cast<std::size_t>(rows));
  for (double& e : s.elevation_rad) in >> e;
  s.azimuth_rad.resize(static_cast<std::size_t>(cols));
  for (double& a : s.azimuth_rad) in >> a;
  std::uint32_t laser_ids;
  in >> laser_ids;
  if (laser_ids != 0 && laser_ids != static_cast<std::uint32_t>(rows))
    THROW_EXCEPTION_FMT("%u laser ids for %d rows", laser_ids, rows);
  s.laser_of_row.resize(laser_ids);
  for (int& l : s.laser_of_row) {
    std::int32_t id;
    in >> id;
    l = id;
  }
  const std::size_t cells = static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols);
  s.range_m.create(rows, cols, CV_32FC1);
  readExactly(in, s.range_m.ptr<float>(0), cells, "sweep ranges");
  std::uint8_t has_ray;
  in >> has_ray;
  if (has_ray > 1) THROW_EXCEPTION_FMT("sweep ray flag %u", static_cast<unsigned>(has_ray));
  if (has_ray) {
    s.ray.create(rows, cols, CV_32FC3);
    readExactly(in, s.ray.ptr<float>(0), cells * 3, "sweep rays");
  }
  return v;
}

SuperpixelMapView readView(mrpt::serialization::CArchive& in) {
  SuperpixelMapView v;
  in >> v.timestamp >> v.sensor_label;
  v.T_map_camera = readPose(in);
  CameraIntrinsics k;
  std::int32_t w, h;
  in >> w >> h >> k.fx >> k.fy >> k.cx >> k.cy;
  for (double& d : k.distortion) in >> d;
  if (w < 1 || h < 1 || static_cast<std::uint32_t>(w) > kMaxImageSide || static_cast<std::uint32_t>(h) > kMaxImageSide ||
      static_cast<std::uint64_t>(w) * static_cast<std::uint64_t>(h) > kMaxImagePixels)
    THROW_EXCEPTION_FMT("image size %dx%d out of range", w, h);
  k.width = w;
  k.height = h;
  v.view.projection = k;
  const std::size_t pixels = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  v.view.depth_m.create(h, w, CV_32FC1);
  readExactly(in, v.view.depth_m.ptr<float>(0), pixels, "depth image");
  SuperpixelSegmentation& seg = v.view.segmentation;
  seg.labels.create(h, w, CV_32SC1);
  std::uint32_t num_runs;
  in >> num_runs;
  if (num_runs > pixels) THROW_EXCEPTION_FMT("%u label runs for %zu pixels", num_runs, pixels);
  int* labels = seg.labels.ptr<int>(0);
  std::size_t filled = 0;
  for (std::uint32_t i = 0; i < num_runs; ++i) {
    std::int32_t label;
    std::uint32_t length;
    in >> label >> length;
    if (length == 0 || length > pixels - filled) THROW_EXCEPTION("label runs do not add up to the image size");
    std::fill(labels + filled, labels + filled + length, label);
    filled += length;
  }
  if (filled != pixels) THROW_EXCEPTION("label runs do not cover the image");
  std::uint32_t num_patches;
  in >> num_patches;
  if (num_patches > pixels) THROW_EXCEPTION_FMT("%u patches for %zu pixels", num_patches, pixels);
  for (std::uint32_t i = 0; i < num_patches; ++i) {
    SurfacePatch p;
    std::int32_t id, count, bx, by, bw, bh;
    in >> id;
    p.id = id;
    p.centroid = readVec(in);
    p.normal = readVec(in);
    in >> p.area_m2 >> count;
    p.pixel_count = count;
    for (int j = 0; j < 9; ++j) in >> p.covariance(j / 3, j % 3);
    in >> p.planarity >> bx >> by >> bw >> bh;
    p.bbox = cv::Rect(bx, by, bw, bh);
    seg.patches.push_back(p);
  }
  seg.adjacency.resize(num_patches);
  for (auto& list : seg.adjacency) {
    std::uint32_t n;
    in >> n;
    if (n > num_patches) THROW_EXCEPTION_FMT("a patch with %u neighbours among %u patches", n, num_patches);
    for (std::uint32_t j = 0; j < n; ++j) {
      std::int32_t id;
      in >> id;
      list.push_back(id);
    }
  }
  std::uint64_t valid, assigned, dropped;
  in >> valid >> assigned >> dropped;
  seg.stats.valid_pixels = valid;
  seg.stats.assigned_pixels = assigned;
  seg.stats.dropped_pixels = dropped;
  std::uint32_t num_colours;
  in >> num_colours;
  if (num_colours != 0 && num_colours != num_patches)
    THROW_EXCEPTION_FMT("%u patch colours for %u patches", num_colours, num_patches);
  v.patch_rgb.resize(num_colours);
  for (Rgb8& c : v.patch_rgb) in >> c[0] >> c[1] >> c[2];
  try {
    checkConsistency(v);
  } catch (const Error& e) {
    THROW_EXCEPTION(e.what());
  }
  return v;
}

}  // namespace

uint8_t CSuperpixelMap::serializeGetVersion() const { return 3; }

void CSuperpixelMap::serializeTo(mrpt::serialization::CArchive& out) const {
  out << genericMapParams;
  out << optionsText(creationOptions) << optionsText(likelihoodOptions) << optionsText(renderOptions);
  out << static_cast<std::uint32_t>(views_.size());
  for (const auto& v : views_) {
    const bool sweep = v.view.returns != nullptr;
    out << static_cast<std::uint8_t>(sweep ? 1 : 0);
    if (sweep)
      writeSweepView(out, v);
    else
      writeView(out, v);
    CSuperpixelMap::TCreationOptions segmentation;  // the view's own, as the map's creation options are written
    segmentation.superpixels = v.view.superpixels;
    out << optionsText(segmentation);
    if (sweep)
      out << static_cast<std::int32_t>(v.view.returns->normalHalfWidth()) << v.view.returns->maxFlatness()
          << v.view.returns->normalNoise() << v.view.returns->planeTolerance();
  }
}

void CSuperpixelMap::serializeFrom(mrpt::serialization::CArchive& in, uint8_t version) {
  if (version > 3) MRPT_THROW_UNKNOWN_SERIALIZATION_VERSION(version);
  try {
    mrpt::maps::TMapGenericParams generic;
    in >> generic;
    std::string creation, likelihood, render;
    in >> creation >> likelihood >> render;
    TCreationOptions c;
    TLikelihoodOptions l;
    TRenderOptions r;
    optionsFromText(creation, c);
    optionsFromText(likelihood, l);
    optionsFromText(render, r);
    std::uint32_t num_views;
    in >> num_views;
    std::vector<SuperpixelMapView> views;
    for (std::uint32_t i = 0; i < num_views; ++i) {
      try {
        std::uint8_t kind = 0;
        if (version >= 2) in >> kind;
        if (kind > 1) THROW_EXCEPTION_FMT("view kind %u (0: depth image, 1: LiDAR sweep)", static_cast<unsigned>(kind));
        if (kind == 1) {
          RangeScan scan;
          SuperpixelMapView v = readSweepView(in, scan);
          std::string text;
          in >> text;
          TCreationOptions segmentation;
          optionsFromText(text, segmentation);
          ReturnsRefineParams returns;
          std::int32_t half_width;
          in >> half_width >> returns.max_flatness;
          if (half_width < 1 || half_width > 100)  // the effective one a view was made with (validate()'s range)
            THROW_EXCEPTION_FMT("the returns' normal half width %d out of range [1, 100]", half_width);
          returns.normal_half_width = half_width;
          returns.normal_noise_m = 0.0;  // version 2: adjacent rows, and the default last gate
          if (version >= 3) in >> returns.normal_noise_m >> returns.gates_m.back();
          try {  // the scan's layout and the parameters are checked here
            v.view = makeRangeView(scan, segmentation.superpixels, returns);
            checkConsistency(v);
          } catch (const Error& e) {
            THROW_EXCEPTION(e.what());
          }
          views.push_back(std::move(v));
        } else {
          views.push_back(readView(in));
          if (version >= 1) {
            std::string text;
            in >> text;
            TCreationOptions segmentation;
            optionsFromText(text, segmentation);
            views.back().view.superpixels = segmentation.superpixels;
          } else {  // version 0: segmented with the map's creation options
            views.back().view.superpixels = c.superpixels;
          }
        }
      } catch (const std::exception& e) {
        THROW_EXCEPTION_FMT("view %u of %u: %s", i, num_views, e.what());
      }
    }
    genericMapParams = generic;
    creationOptions = c;
    likelihoodOptions = l;
    renderOptions = r;
    views_ = std::move(views);
    ++content_version_;
  } catch (const std::exception& e) {
    THROW_EXCEPTION_FMT("gasp::CSuperpixelMap: corrupt serialized map: %s", mrpt::exception_to_str(e).c_str());
  }
}

}  // namespace gasp
