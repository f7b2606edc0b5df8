// CSuperpixelMap::getVisualizationInto: patches as oriented discs (one triangle set) or their
// pixels as coloured points, in the map frame.
#include <mrpt/opengl/CPointCloudColoured.h>
#include <mrpt/opengl/CSetOfObjects.h>
#include <mrpt/opengl/CSetOfTriangles.h>

#include <cmath>

#include "gasp/mrpt/CSuperpixelMap.h"

namespace gasp {

namespace {

constexpr int kDiscSegments = 16;

mrpt::math::TPoint3Df toPoint(const Eigen::Vector3d& p) {
  return {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())};
}

mrpt::opengl::CSetOfTriangles::Ptr discs(const std::vector<MapPatch>& patches) {
  auto out = mrpt::opengl::CSetOfTriangles::Create();
  out->setName("gasp_superpixel_discs");
  out->reserve(patches.size() * kDiscSegments);
  for (const MapPatch& p : patches) {
    // An orthonormal basis (u, v) of the patch plane.
    const Eigen::Vector3d n = p.normal;
    const Eigen::Vector3d a = std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    const Eigen::Vector3d u = n.cross(a).normalized(), v = n.cross(u);
    const mrpt::img::TColor colour(p.rgb[0], p.rgb[1], p.rgb[2]);
    for (int k = 0; k < kDiscSegments; ++k) {
      const double a0 = 2 * M_PI * k / kDiscSegments, a1 = 2 * M_PI * (k + 1) / kDiscSegments;
      const Eigen::Vector3d q0 = p.centroid + p.radius_m * (std::cos(a0) * u + std::sin(a0) * v);
      const Eigen::Vector3d q1 = p.centroid + p.radius_m * (std::cos(a1) * u + std::sin(a1) * v);
      mrpt::opengl::TTriangle t(toPoint(p.centroid), toPoint(q0), toPoint(q1));
      t.setColor(colour);
      out->insertTriangle(t);
    }
  }
  return out;
}

mrpt::opengl::CPointCloudColoured::Ptr points(const std::vector<SuperpixelMapView>& views, int step) {
  auto out = mrpt::opengl::CPointCloudColoured::Create();
  out->setName("gasp_superpixel_points");
  out->setPointSize(2.0f);
  for (const SuperpixelMapView& view : views) {
    const SuperpixelSegmentation& seg = view.view.segmentation;
    const ViewProjection& k = view.view.projection;  // a camera's pinhole or a sweep's grid
    for (int r = 0; r < seg.labels.rows; r += step) {
      const int* l = seg.labels.ptr<int>(r);
      const float* z = view.view.depth_m.ptr<float>(r);
      for (int c = 0; c < seg.labels.cols; c += step) {
        if (l[c] < 0) continue;
        const std::size_t i = static_cast<std::size_t>(l[c]);
        const Rgb8 rgb = view.patch_rgb.empty() ? normalColour(seg.patches[i].normal) : view.patch_rgb[i];
        const Eigen::Vector3d p = view.T_map_camera * k.unproject(c, r, z[c]);
        out->push_back(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()),
                       rgb[0] / 255.0f, rgb[1] / 255.0f, rgb[2] / 255.0f);
      }
    }
  }
  return out;
}

}  // namespace

void CSuperpixelMap::getVisualizationInto(mrpt::opengl::CSetOfObjects& o) const {
  if (!genericMapParams.enableSaveAs3DObject) return;
  if (renderOptions.style == TRenderOptions::Style::discs)
    o.insert(discs(patchesInMapFrame()));
  else
    o.insert(points(views_, renderOptions.point_step_px));
}

}  // namespace gasp
