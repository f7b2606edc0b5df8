#pragma once
/// \file object_move.h Objects that move between frames: a dynamic scene (a chair pushed, a box
/// carried off), so that what a moved object does to registration can be measured with exact
/// ground truth (docs/simulator.md, "Moved objects").
#include <string>
#include <vector>

#include "gasp/sim/scene.h"

namespace gasp::sim {

/// The objects whose names start with `prefix` (all parts of a piece of furniture: "chair" takes
/// chair_seat, chair_base and chair_back) stand at their place before frame `at_frame` and, from
/// `at_frame` on, turned together by `yaw_deg` about the vertical through the mean of their
/// origins and then shifted by `shift_m`.
struct ObjectMove {
  std::string prefix;
  Eigen::Vector3d shift_m = Eigen::Vector3d::Zero();  ///< world frame [m]
  double yaw_deg = 0.0;                               ///< about the world z axis [deg]
  int at_frame = 1;                                   ///< first frame at the new place (>= 1)
};

/// Parses "PREFIX:DX,DY,DZ@FRAME" or "PREFIX:DX,DY,DZ,YAW_DEG@FRAME" (gasp-simulate --move), for
/// example "chair:0,-0.6,0@30". Throws gasp::Error naming the text and the expected form.
ObjectMove parseObjectMove(const std::string& text);

/// Applies the moves to a scene of `frames` frames: each moved object exists up to at_frame - 1,
/// and a copy named "<name>@moved" (new surface ids) from at_frame on. Throws gasp::Error when a
/// prefix matches no object, an object is matched by two moves, at_frame is outside
/// [1, frames - 1] or not after the frame the object appears (the occluder appears midway), or a
/// number is not finite.
void applyObjectMoves(Scene& scene, const std::vector<ObjectMove>& moves, int frames);

}  // namespace gasp::sim
