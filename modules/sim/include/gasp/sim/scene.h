#pragma once
/// \file scene.h A procedural scene: primitives placed in the world, each face with a surface id.
///
/// World frame: z up, metres; the floor of the room scenes is z = 0.
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "gasp/core/pose.h"
#include "gasp/sim/camera_path.h"
#include "gasp/sim/shapes.h"

namespace gasp::sim {

/// One primitive placed in the world. Face f of the shape has surface id first_surface_id + f.
struct SceneObject {
  std::string name;                                      ///< unique within the scene
  Shape shape;                                           ///< geometry in the object frame
  Isometry3 T_world_object = Isometry3::Identity();      ///< placement
  std::uint16_t first_surface_id = 0;                    ///< assigned by Scene::add (>= 1)
  int visible_from_frame = 0;  ///< the object exists from this frame index on (occluders)
  /// ... and before this frame index (objects moved away, object_move.h)
  int visible_until_frame = std::numeric_limits<int>::max();

  /// Surface id of a face.
  std::uint16_t surfaceId(int face) const {
    return static_cast<std::uint16_t>(first_surface_id + face);
  }
  /// True when a surface id belongs to this object.
  bool ownsSurface(std::uint16_t id) const {
    return id >= first_surface_id && id < first_surface_id + faceCount(shape);
  }
  bool visibleAt(int frame_index) const {
    return frame_index >= visible_from_frame && frame_index < visible_until_frame;
  }
};

/// A list of objects (a room is an object of shape Room). Surface id 0 means "no surface".
struct Scene {
  std::string name;         ///< the name makeScene() knows it by
  std::string description;  ///< one line
  /// True for the degenerate and plane-dominated scenes (plane, corridor, floor_*, ...): no
  /// occluder is added to them.
  bool degenerate = false;
  /// How the camera moves: the room tour of makeCameraPath() when empty, else this hand-held view
  /// (makeHandHeldPath; the plane-dominated scenes).
  std::optional<HandHeldView> hand_held;
  /// ... or this walk through the scene (makeWalkPath; two_rooms). No occluder is added to it.
  std::vector<WalkWaypoint> walk;
  std::vector<SceneObject> objects;

  /// Appends an object, giving its faces the next free surface ids; returns its first id.
  /// Throws gasp::Error for a duplicate name or when the ids would exceed 65535.
  std::uint16_t add(const std::string& object_name, const Shape& shape,
                    const Isometry3& T_world_object, int visible_from_frame = 0);
  /// Highest surface id in use (0 for an empty scene).
  std::uint16_t maxSurfaceId() const;
  /// The object with that name; throws gasp::Error naming the scene when there is none.
  const SceneObject& object(const std::string& object_name) const;
  /// The object owning a surface id, or nullptr.
  const SceneObject* objectOfSurface(std::uint16_t id) const;
};

/// Names makeScene() accepts: room (the default), repeated, sparse, plane, corridor, and the
/// plane-dominated scenes seen by a hand-held camera: floor_0, floor_1, floor_3, floor_6 (a floor
/// with that many low objects), wall_door, corridor_walk, table_top; two_rooms, walked through (a
/// long loop); and street, an outdoor street walked along at a LiDAR's height.
std::vector<std::string> sceneNames();

/// The default scene's name ("room").
inline std::string defaultSceneName() { return "room"; }

/// A scene by name (see sceneNames()); throws gasp::Error listing the valid names otherwise.
/// The room-tour scenes are laid out for the camera path of camera_path.h (the camera moves around
/// x in [-1, 0.2], y in [-0.7, 0.6] at 1.2-1.4 m height and looks towards +x); the others carry
/// their hand-held view.
Scene makeScene(const std::string& name);

/// Pose helper: translation (x, y, z) [m] and a rotation of yaw_deg about the world z axis.
Isometry3 placeAt(double x, double y, double z, double yaw_deg = 0.0);

}  // namespace gasp::sim
