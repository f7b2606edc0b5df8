#pragma once
/// \file view_bytes.h A segmented depth view as bytes and back, exactly: for handing a keyframe's
/// view to another process once (a map-building job spread over processes), rather than
/// segmenting it again there.
///
/// The bytes hold the depth image, the projection (a pinhole's intrinsics, or a spherical grid with
/// its ray table), the segmentation (labels, patches, adjacency, counts; not its timings) and, for
/// a LiDAR view, its sweep (returns_stage.h), whose returns' normals are fitted again on reading
/// (deterministic). Numbers are written as the machine holds them (little-endian IEEE doubles
/// and floats on every platform GASP builds on; the header says which, and reading refuses
/// another). The superpixel parameters the view was made with, and the returns' settings, are not
/// in the bytes: the reader gives them (the processes of one job load the same parameters).
#include <string>
#include <string_view>

#include "gasp/pipeline/depth_view.h"
#include "gasp/pipeline/returns_stage.h"

namespace gasp {

/// The bytes of `view`.
std::string viewBytes(const DepthView& view);

/// The view written by viewBytes(), with `superpixels` as its DepthView::superpixels and, for a
/// LiDAR view, its returns made with `returns`. Throws gasp::Error saying what is wrong for bytes
/// that are not a view's (another format or byte order, truncated, sizes out of range, labels or
/// adjacency naming no patch).
DepthView viewFromBytes(std::string_view bytes, const SuperpixelParams& superpixels,
                        const ReturnsRefineParams& returns = {});

}  // namespace gasp
