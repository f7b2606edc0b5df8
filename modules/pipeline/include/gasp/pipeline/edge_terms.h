#pragma once
/// \file edge_terms.h Dense point-to-line terms along occluding edges, for the final refinement of
/// a pair's pose. Point-to-plane terms cannot stop a pose sliding along a plane (a floor, a
/// cabinet top): every point stays on its plane. Where a surface ends at a depth discontinuity
/// its boundary is a 3D curve that pins the slide. Each sampled source edge point (foreground
/// side of a depth jump) is mapped by the current T_target_source and paired with the nearest
/// target edge point; the residual is its offset perpendicular to the target edge's local
/// direction (two point-to-plane terms with normals perpendicular to the edge), so points may
/// still move along the edge, where nothing corresponds.
#include <memory>
#include <vector>

#include "gasp/core/pose.h"
#include "gasp/pipeline/depth_view.h"
#include "gasp/registration/correspondence.h"

namespace gasp {

struct EdgeTermParams {
  /// A pixel is an edge pixel when a pixel 1 or 2 steps away (4 directions) has valid depth at
  /// least min_jump_m + jump_per_m2 * z^2 further away (the foreground side of a depth jump).
  double min_jump_m = 0.05;
  double jump_per_m2 = 0.02;  ///< [1/m]
  /// Source edge pixels used: one per block of (pixel_step / 2)^2 pixels (pixel_step >= 1), about
  /// two per pixel_step pixels along an edge of any direction (up to sqrt(2) more on diagonals);
  /// the target keeps every other edge pixel (those with (u + v) even).
  int pixel_step = 12;
  int line_neighbours = 8;    ///< target edge points fitted for the local edge direction (>= 3)
  double max_distance_m = 0.05;  ///< gate on the distance to the nearest target edge point [m]
  double weight = 2.0;           ///< of each term, against the point-to-plane terms' 1
};

/// Throws gasp::Error for a parameter out of range.
void validate(const EdgeTermParams& params);

/// Edge pixels of a view, one per (pixel_step / 2)^2 block (the one nearest the block's centre
/// among the edge pixels with (u + v) even), as 3D points [m] (camera frame) with their
/// pixel coordinates, in block raster order. The view's depth must be CV_32FC1 (gasp::Error).
struct EdgePoints {
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector2i> pixels;
};
EdgePoints findEdgePoints(const DepthView& view, const EdgeTermParams& params = {});

/// The target side, built once per pair: the target's edge points in a KD-tree, each with the two
/// unit normals of its local edge line (principal axis of its line_neighbours nearest edge
/// points; points where the edge has no dominant direction -- a corner, a blob -- are not used).
class EdgeTargets {
 public:
  EdgeTargets(const DepthView& target, const EdgeTermParams& params = {});
  ~EdgeTargets();
  EdgeTargets(const EdgeTargets&) = delete;
  EdgeTargets& operator=(const EdgeTargets&) = delete;
  std::size_t size() const;

  /// The terms for the current pose: two per source edge point whose
  /// nearest target edge point is within max_distance_m and has a line direction.
  std::vector<PointToPlane> terms(const EdgePoints& source, const Isometry3& T_target_source,
                                  double max_distance_m) const;

 private:
  struct Index;
  std::unique_ptr<Index> index_;
  EdgeTermParams params_;
};

/// Convenience: findEdgePoints(source) against EdgeTargets(target) at params.max_distance_m.
std::vector<PointToPlane> edgeTerms(const DepthView& source, const DepthView& target,
                                    const Isometry3& T_target_source, const EdgeTermParams& params = {});

}  // namespace gasp
