#include "gasp/pipeline/view_bytes.h"

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "gasp/core/byte_stream.h"

namespace gasp {

std::string viewBytes(const DepthView& view) {
  ByteWriter w;
  w.writeHeader("GVW1");
  w.putMat(view.depth_m);
  w.put(static_cast<std::uint8_t>(view.projection.isPinhole() ? 0 : 1));
  if (view.projection.isPinhole()) {
    w.putIntrinsics(view.projection.pinhole());
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
    w.putMatrix(p.centroid);
    w.putMatrix(p.normal);
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
  w.putFlag(view.returns != nullptr);
  if (view.returns) w.putScan(view.returns->scan());
  return w.take();
}

DepthView viewFromBytes(std::string_view bytes, const SuperpixelParams& superpixels, const ReturnsRefineParams& returns) {
  ByteReader r(bytes, "view bytes");
  r.readHeader("GVW1");
  DepthView v;
  v.depth_m = r.getMat("the depth", CV_32FC1);
  const auto kind = r.get<std::uint8_t>("the projection");
  if (kind == 0) {
    v.projection = ViewProjection(r.getIntrinsics("the intrinsics"));
  } else if (kind == 1) {
    SphericalGrid g;
    g.elevation_rad = r.getVector<double>("the grid's elevations");
    g.azimuth_first_rad = r.get<double>("the grid");
    g.azimuth_step_rad = r.get<double>("the grid");
    g.columns = r.get<std::int32_t>("the grid");
    g.ray = r.getMat("the grid's rays", CV_32FC3);
    v.projection = ViewProjection::spherical(std::move(g));  // validates it
  } else {
    r.fail("an unknown projection");
  }
  if (!v.depth_m.empty() && (v.depth_m.cols != v.projection.width() || v.depth_m.rows != v.projection.height()))
    r.fail("the depth image's size is not the projection's");
  SuperpixelSegmentation& seg = v.segmentation;
  seg.labels = r.getMat("the labels", CV_32SC1);
  const std::size_t n = r.getSize(4 + 3 * 8 + 3 * 8 + 8 + 4 + 9 * 8 + 8 + 4 * 4, "the patches");
  seg.patches.resize(n);
  for (SurfacePatch& p : seg.patches) {
    p.id = r.get<std::int32_t>("a patch");
    p.centroid = r.getMatrix<Eigen::Vector3d>("a patch");
    p.normal = r.getMatrix<Eigen::Vector3d>("a patch");
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
      if (j < 0 || static_cast<std::size_t>(j) >= n) r.fail("the adjacency names no patch");
  }
  seg.stats.valid_pixels = r.getSize(0, "the counts");
  seg.stats.assigned_pixels = r.getSize(0, "the counts");
  seg.stats.dropped_pixels = r.getSize(0, "the counts");
  if (seg.labels.empty() && n > 0) r.fail("patches without labels");
  if (!seg.labels.empty()) {
    if (seg.labels.size() != v.depth_m.size()) r.fail("the labels' size is not the depth image's");
    for (int row = 0; row < seg.labels.rows; ++row)
      for (int col = 0; col < seg.labels.cols; ++col)
        if (const int l = seg.labels.at<int>(row, col); l < -1 || (l >= 0 && static_cast<std::size_t>(l) >= n))
          r.fail("a label names no patch");
  }
  if (r.getFlag("the sweep")) v.returns = std::make_shared<const SweepReturns>(r.getScan(), returns);  // validates the scan
  r.expectEnd();
  v.superpixels = superpixels;
  return v;
}

}  // namespace gasp
