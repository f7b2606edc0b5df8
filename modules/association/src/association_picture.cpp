#include "gasp/association/association_picture.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cstdio>
#include <string>

#include "gasp/core/depth_image.h"
#include "gasp/core/error.h"
#include "gasp/superpixels/segmentation_picture.h"

namespace gasp {

namespace {

/// One view: colour of patch id -> colours[id] (grey when unassociated), shaded by depth.
void paintView(const cv::Mat& depth, const SuperpixelSegmentation& seg, const std::vector<cv::Vec3b>& colours,
               cv::Mat out) {
  if (depth.type() != CV_32FC1 || depth.size() != seg.labels.size())
    throw Error("drawAssociations: depth must be CV_32FC1 of the label image's size");
  for (int v = 0; v < depth.rows; ++v)
    for (int u = 0; u < depth.cols; ++u) {
      const float z = depth.at<float>(v, u);
      if (!isValidDepth(z)) continue;
      const float zr = u + 1 < depth.cols && isValidDepth(depth.at<float>(v, u + 1)) ? depth.at<float>(v, u + 1) : z;
      const float zd = v + 1 < depth.rows && isValidDepth(depth.at<float>(v + 1, u)) ? depth.at<float>(v + 1, u) : z;
      const float shade = std::clamp(0.75f + 40.0f * ((zr - z) + (zd - z)) / z, 0.35f, 1.0f);
      const int l = seg.labels.at<int>(v, u);
      const cv::Vec3b c = l >= 0 ? colours[static_cast<std::size_t>(l)] : cv::Vec3b(40, 40, 40);
      out.at<cv::Vec3b>(v, u) = cv::Vec3b(static_cast<std::uint8_t>(c[0] * shade), static_cast<std::uint8_t>(c[1] * shade),
                                          static_cast<std::uint8_t>(c[2] * shade));
    }
}

cv::Point pixelOf(const Eigen::Vector3d& p, const CameraIntrinsics& k) {
  if (!(p.z() > 0)) return {-1, -1};
  return {static_cast<int>(std::lround(k.fx * p.x() / p.z() + k.cx)), static_cast<int>(std::lround(k.fy * p.y() / p.z() + k.cy))};
}

/// The legend over a dark band at the top, sized to the picture's width.
void drawLegend(cv::Mat& out, const std::string& legend) {
  if (legend.empty()) return;
  const int font = cv::FONT_HERSHEY_SIMPLEX;
  double scale = 0.5;
  int baseline = 0;
  cv::Size size = cv::getTextSize(legend, font, scale, 1, &baseline);
  if (size.width > out.cols - 8) {
    scale *= static_cast<double>(out.cols - 8) / size.width;
    size = cv::getTextSize(legend, font, scale, 1, &baseline);
  }
  const int band = std::min(out.rows, size.height + baseline + 8);
  cv::Mat top = out(cv::Rect(0, 0, out.cols, band));
  top *= 0.35;
  cv::putText(out, legend, cv::Point(4, size.height + 4), font, scale, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
}

}  // namespace

std::string associationLegend(const std::string& what, std::size_t n, const std::vector<unsigned char>& correct) {
  std::string s = what + " associations: " + std::to_string(n);
  if (correct.empty() || correct.size() != n) return s + (n > 0 ? " (no ground truth)" : "");
  const std::size_t right = static_cast<std::size_t>(std::count(correct.begin(), correct.end(), 1));
  char precision[32];
  std::snprintf(precision, sizeof precision, "%.3f", static_cast<double>(right) / static_cast<double>(n));
  return s + " -- " + std::to_string(right) + " right, " + std::to_string(n - right) + " wrong (precision " + precision +
         "); green right, red wrong";
}

cv::Mat drawAssociations(const cv::Mat& depth_a, const SuperpixelSegmentation& a, const CameraIntrinsics& intrinsics_a,
                         const cv::Mat& depth_b, const SuperpixelSegmentation& b, const CameraIntrinsics& intrinsics_b,
                         const std::vector<PatchAssociation>& associations, const std::vector<unsigned char>& correct,
                         const AssociationPictureOptions& options) {
  if (!correct.empty() && correct.size() != associations.size())
    throw Error("drawAssociations: one correctness flag per association expected");
  const cv::Vec3b grey(150, 150, 150);
  std::vector<cv::Vec3b> ca(a.patches.size(), grey), cb(b.patches.size(), grey);
  for (std::size_t k = 0; k < associations.size(); ++k) {
    const auto& s = associations[k];
    if (s.a < 0 || s.b < 0 || static_cast<std::size_t>(s.a) >= ca.size() || static_cast<std::size_t>(s.b) >= cb.size())
      throw Error("drawAssociations: association names a patch that does not exist");
    ca[static_cast<std::size_t>(s.a)] = cb[static_cast<std::size_t>(s.b)] = patchColour(static_cast<int>(k));
  }
  const int w = depth_a.cols, h = std::max(depth_a.rows, depth_b.rows);
  cv::Mat out(h, w + depth_b.cols, CV_8UC3, cv::Scalar(0, 0, 0));
  paintView(depth_a, a, ca, out(cv::Rect(0, 0, depth_a.cols, depth_a.rows)));
  paintView(depth_b, b, cb, out(cv::Rect(w, 0, depth_b.cols, depth_b.rows)));
  drawLegend(out, options.legend);
  if (associations.empty() || options.max_lines <= 0) return out;
  const std::size_t step = std::max<std::size_t>(1, associations.size() / static_cast<std::size_t>(options.max_lines));
  for (std::size_t k = 0; k < associations.size(); k += step) {
    const auto& s = associations[k];
    const cv::Point pa = pixelOf(a.patches[static_cast<std::size_t>(s.a)].centroid, intrinsics_a);
    cv::Point pb = pixelOf(b.patches[static_cast<std::size_t>(s.b)].centroid, intrinsics_b);
    pb.x += w;
    const cv::Scalar colour = correct.empty() ? cv::Scalar(255, 255, 255)
                              : correct[k]    ? cv::Scalar(0, 220, 0)
                                              : cv::Scalar(0, 0, 255);
    cv::line(out, pa, pb, colour, 1, cv::LINE_AA);
    cv::circle(out, pa, 3, colour, -1, cv::LINE_AA);
    cv::circle(out, pb, 3, colour, -1, cv::LINE_AA);
  }
  return out;
}

}  // namespace gasp
