#pragma once
/// \file association_picture.h A picture of the associations between two views, like the paper's
/// first figure: the views side by side over shaded depth, associated patches in the same colour
/// in both views, unassociated patches grey, and lines joining the centroids of a sample of
/// associations (green when known correct, red when known wrong, white when unknown), and a
/// legend line at the top (associationLegend()).
#include <opencv2/core.hpp>

#include <string>
#include <vector>

#include "gasp/association/view_association.h"
#include "gasp/core/camera_intrinsics.h"
#include "gasp/superpixels/surface_patch.h"

namespace gasp {

struct AssociationPictureOptions {
  int max_lines = 60;  ///< lines drawn for at most this many associations (evenly sampled)
  std::string legend;  ///< one line of text drawn over the top of the picture (empty: none)
};

/// The legend of a picture of `n` associations of the kind `what` ("verified", "free"): their
/// count and, with one correctness flag per association, how many are right and wrong and the
/// precision, e.g. "verified associations: 635 -- 630 right, 5 wrong (precision 0.992); green
/// right, red wrong". Without flags: "... (no ground truth)".
std::string associationLegend(const std::string& what, std::size_t n, const std::vector<unsigned char>& correct);

/// BGR picture, 2 w x h. `correct` is empty or one flag per association (1 correct, 0 wrong).
/// Throws gasp::Error when a depth image does not match its label image, or an association
/// names a patch that does not exist.
cv::Mat drawAssociations(const cv::Mat& depth_a, const SuperpixelSegmentation& a, const CameraIntrinsics& intrinsics_a,
                         const cv::Mat& depth_b, const SuperpixelSegmentation& b, const CameraIntrinsics& intrinsics_b,
                         const std::vector<PatchAssociation>& associations,
                         const std::vector<unsigned char>& correct = {},
                         const AssociationPictureOptions& options = {});

}  // namespace gasp
