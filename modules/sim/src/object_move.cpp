#include "gasp/sim/object_move.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>
#include <sstream>

#include "gasp/core/error.h"

namespace gasp::sim {

ObjectMove parseObjectMove(const std::string& text) {
  const auto fail = [&text]() -> ObjectMove {
    throw Error("object move '" + text + "': expected PREFIX:DX,DY,DZ@FRAME or PREFIX:DX,DY,DZ,YAW_DEG@FRAME "
                "(metres, degrees), e.g. chair:0,-0.6,0@30");
  };
  const auto colon = text.find(':'), at = text.rfind('@');
  if (colon == std::string::npos || colon == 0 || at == std::string::npos || at < colon) return fail();
  ObjectMove m;
  m.prefix = text.substr(0, colon);
  const std::string numbers_text = text.substr(colon + 1, at - colon - 1);
  if (numbers_text.empty() || numbers_text.back() == ',') return fail();
  for (const char ch : numbers_text)
    if (std::isspace(static_cast<unsigned char>(ch))) return fail();
  std::vector<double> numbers;
  std::stringstream list(numbers_text);
  for (std::string item; std::getline(list, item, ',');) {
    std::size_t used = 0;
    try {
      numbers.push_back(std::stod(item, &used));
    } catch (const std::exception&) {
      return fail();
    }
    if (used != item.size() || !std::isfinite(numbers.back())) return fail();
  }
  if (numbers.size() != 3 && numbers.size() != 4) return fail();
  m.shift_m = Eigen::Vector3d(numbers[0], numbers[1], numbers[2]);
  if (numbers.size() == 4) m.yaw_deg = numbers[3];
  const std::string frame = text.substr(at + 1);
  if (frame.empty() || !std::isdigit(static_cast<unsigned char>(frame[0]))) return fail();
  std::size_t used = 0;
  try {
    m.at_frame = std::stoi(frame, &used);
  } catch (const std::exception&) {
    return fail();
  }
  if (used != frame.size()) return fail();
  return m;
}

void applyObjectMoves(Scene& scene, const std::vector<ObjectMove>& moves, int frames) {
  std::set<std::string> moved;
  for (const ObjectMove& m : moves) {
    if (m.prefix.empty()) throw Error("object move: empty object name prefix");
    if (!m.shift_m.allFinite() || !std::isfinite(m.yaw_deg))
      throw Error("object move '" + m.prefix + "': shift and yaw must be finite");
    if (m.at_frame < 1 || m.at_frame > frames - 1)
      throw Error("object move '" + m.prefix + "': frame " + std::to_string(m.at_frame) + " is outside [1, " +
                  std::to_string(frames - 1) + "]");
    std::vector<std::size_t> parts;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < scene.objects.size(); ++k) {
      const SceneObject& o = scene.objects[k];
      if (o.name.rfind(m.prefix, 0) != 0 || o.name.find('@') != std::string::npos) continue;  // not a prefix, or a copy
      if (m.at_frame <= o.visible_from_frame)
        throw Error("object move '" + m.prefix + "': object '" + o.name + "' appears only at frame " +
                    std::to_string(o.visible_from_frame) + ", so a move at frame " + std::to_string(m.at_frame) +
                    " would move nothing");
      if (!moved.insert(o.name).second)
        throw Error("object move '" + m.prefix + "': object '" + o.name + "' is moved by two moves");
      parts.push_back(k);
      centre += o.T_world_object.translation();
    }
    if (parts.empty()) {
      std::string names;
      for (const auto& o : scene.objects) names += (names.empty() ? "" : ", ") + o.name;
      throw Error("object move: scene '" + scene.name + "' has no object whose name starts with '" + m.prefix +
                  "' (objects: " + names + ")");
    }
    centre /= static_cast<double>(parts.size());
    centre.z() = 0.0;  // the vertical axis through the parts' mean origin
    Isometry3 T_move = Isometry3::Identity();
    T_move.linear() = Eigen::AngleAxisd(m.yaw_deg * EIGEN_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T_move.translation() = centre + m.shift_m - T_move.linear() * centre;
    for (const std::size_t k : parts) {
      scene.objects[k].visible_until_frame = m.at_frame;
      const SceneObject o = scene.objects[k];  // a copy: add() may reallocate
      scene.add(o.name + "@moved", o.shape, T_move * o.T_world_object, std::max(o.visible_from_frame, m.at_frame));
    }
  }
}

}  // namespace gasp::sim
