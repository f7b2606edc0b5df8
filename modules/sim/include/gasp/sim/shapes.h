#pragma once
/// \file shapes.h Primitive surfaces with exact ray intersection, each expressed in its own
/// object frame (the scene places it with T_world_object).
#include <Eigen/Core>
#include <string>
#include <variant>

namespace gasp::sim {

/// Nearest intersection of the ray origin + t * dir (t > t_min) with a shape, in the shape's frame.
/// `dir` need not be unit length: the renderer uses camera rays with z = 1, so t is the depth z [m].
struct RayHit {
  double t = 0.0;                                      ///< ray parameter of the hit
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< unit surface normal (shape frame)
  int face = 0;                                        ///< face index within the shape
};

/// Finite rectangle in the plane z = 0: |x| <= half_x, |y| <= half_y [m]. Two-sided; normal +z.
/// One face (0).
struct Rectangle {
  double half_x = 0.5;  ///< [m]
  double half_y = 0.5;  ///< [m]
};

/// Solid box centred at the origin, |x|, |y|, |z| <= half_extents [m]. Faces 0..5 are
/// -x, +x, -y, +y, -z, +z; normals point outward.
struct Box {
  Eigen::Vector3d half_extents{0.5, 0.5, 0.5};  ///< [m]
};

/// Capped cylinder about the z axis, centred at the origin. Faces: 0 side, 1 bottom cap (-z),
/// 2 top cap (+z); normals point outward.
struct Cylinder {
  double radius = 0.5;       ///< [m]
  double half_height = 0.5;  ///< [m]
};

/// Sphere centred at the origin. One face (0); normals point outward.
struct Sphere {
  double radius = 0.5;  ///< [m]
};

/// The inside of a box (a room seen from within), centred at the origin. Faces as Box:
/// 0..5 = wall -x, wall +x, wall -y, wall +y, floor (-z), ceiling (+z); normals point inward.
/// Seen from outside, the near walls are transparent (only inner faces are hit).
struct Room {
  Eigen::Vector3d half_extents{4.0, 3.0, 1.5};  ///< [m]
};

/// Any primitive.
using Shape = std::variant<Rectangle, Box, Cylinder, Sphere, Room>;

bool intersect(const Rectangle& s, const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
               double t_min, RayHit& hit);
bool intersect(const Box& s, const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
               double t_min, RayHit& hit);
bool intersect(const Cylinder& s, const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
               double t_min, RayHit& hit);
bool intersect(const Sphere& s, const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
               double t_min, RayHit& hit);
bool intersect(const Room& s, const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
               double t_min, RayHit& hit);
/// Dispatches to the shape's intersect(); true (and `hit` set) for the nearest hit with t > t_min.
bool intersect(const Shape& s, const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
               double t_min, RayHit& hit);

/// Number of faces (each gets its own surface id in a scene).
int faceCount(const Shape& s);
/// Radius of a sphere about the frame origin enclosing the shape [m]; +infinity for a Room.
double boundingRadius(const Shape& s);
/// "rectangle", "box", "cylinder", "sphere" or "room".
std::string shapeTypeName(const Shape& s);
/// Readable name of a face: "-x", "side", "floor", ...
std::string faceName(const Shape& s, int face);

}  // namespace gasp::sim
