#include "gasp/sim/scene.h"

#include <cmath>
#include <limits>

#include "gasp/core/error.h"

namespace gasp::sim {

std::uint16_t Scene::add(const std::string& object_name, const Shape& shape,
                         const Isometry3& T_world_object, int visible_from_frame) {
  for (const auto& o : objects)
    if (o.name == object_name)
      throw Error("scene '" + name + "': object name '" + object_name + "' used twice");
  const int first = maxSurfaceId() + 1;
  if (first + faceCount(shape) - 1 > std::numeric_limits<std::uint16_t>::max())
    throw Error("scene '" + name + "': more than 65535 surfaces");
  SceneObject obj;
  obj.name = object_name;
  obj.shape = shape;
  obj.T_world_object = T_world_object;
  obj.first_surface_id = static_cast<std::uint16_t>(first);
  obj.visible_from_frame = visible_from_frame;
  objects.push_back(obj);
  return obj.first_surface_id;
}

std::uint16_t Scene::maxSurfaceId() const {
  int m = 0;
  for (const auto& o : objects) m = std::max(m, o.first_surface_id + faceCount(o.shape) - 1);
  return static_cast<std::uint16_t>(m);
}

const SceneObject& Scene::object(const std::string& object_name) const {
  for (const auto& o : objects)
    if (o.name == object_name) return o;
  throw Error("scene '" + name + "' has no object named '" + object_name + "'");
}

const SceneObject* Scene::objectOfSurface(std::uint16_t id) const {
  for (const auto& o : objects)
    if (o.ownsSurface(id)) return &o;
  return nullptr;
}

Isometry3 placeAt(double x, double y, double z, double yaw_deg) {
  Isometry3 T = Isometry3::Identity();
  T.linear() = Eigen::AngleAxisd(yaw_deg * EIGEN_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, y, z);
  return T;
}

}  // namespace gasp::sim
