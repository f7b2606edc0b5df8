#pragma once
// Plane models of patches and priority region growing of patches into unlabelled pixels, shared by
// the clean-up on the grid and the full-resolution finish.
#include <Eigen/Core>
#include <vector>

#include "gasp/core/view_projection.h"
#include "gasp/superpixels/depth_links.h"

namespace gasp::detail {

struct PlaneModel {
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero();
  Eigen::Vector3f normal = Eigen::Vector3f::Zero();  ///< unit
  float area = 0.0f;                                 ///< [m^2], pixel areas foreshortened by `normal`
  int pixels = 0;
};

/// Models of labels 0..count-1 (L: n_px labels, -1 = none): mean point, mean pixel normal (facing
/// the camera from the centroid when no pixel has one), area (a second pass; left 0 when
/// with_area is false). normals: zero where a pixel has none.
std::vector<PlaneModel> planeModels(const int* L, std::size_t n_px, int count, const Eigen::Vector3f* points,
                                    const Eigen::Vector3f* normals, const ViewProjection& k, float min_cos,
                                    bool with_area = true);

/// The normal of a pixel: normals[i], or, with `cell` given, normals[cell[i]] (zero where
/// cell[i] < 0) -- full-resolution pixels that take the normal of a grid cell.
struct PixelNormals {
  const Eigen::Vector3f* normals = nullptr;
  const int* cell = nullptr;
  Eigen::Vector3f operator()(int i) const {
    if (!cell) return normals[i];
    return cell[i] >= 0 ? normals[cell[i]] : Eigen::Vector3f::Zero();
  }
};

struct GrowthLimits {
  float max_cost = 0.0f;  ///< [m]; costlier pixels are not taken
  float max_area = 0.0f;  ///< [m^2]; a patch this large stops growing (infinity: no limit)
  float normal_weight_m = 0.0f;
};

/// Grows labelled patches into unlabelled, linked valid pixels, cheapest first: cost = distance
/// to the patch plane + normal_weight_m (1 - |n_patch . n_pixel|) (no normal term without a pixel
/// normal). Growth crosses links only, so patches stay contiguous. models' pixel counts (and areas,
/// with an area limit) are updated. Returns the number of pixels labelled. unlabelled: when given,
/// the only unlabelled pixels there are (saves scanning the image for them).
int growPatches(int* L, const DepthLinks& links, const Eigen::Vector3f* points, const PixelNormals& normals,
                std::vector<PlaneModel>& models, const GrowthLimits& limits, const ViewProjection& k,
                float min_cos, const std::vector<int>* unlabelled = nullptr);

}  // namespace gasp::detail
