// The named scenes of makeScene(). Laid out around the camera path of camera_path.cpp: the camera
// stays near x in [-1, 0.2], y in [-0.7, 0.6], z in [1.2, 1.4] and looks towards +x (wide
// baseline, roll, occluder) and towards -y (partial-overlap pan).
#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <utility>

#include "gasp/core/error.h"
#include "gasp/sim/scene.h"

namespace gasp::sim {

namespace {

Box box(double hx, double hy, double hz) { return Box{Eigen::Vector3d(hx, hy, hz)}; }

/// Room x in [-2.0, 3.2], y in [-2.5, 2.5], z in [0, 2.8] (5.2 x 5 x 2.8 m): walls within Kinect
/// range (at most ~4.5 m from the camera path), where its depth noise stays moderate.
void addRoom(Scene& s) {
  s.add("room", Room{Eigen::Vector3d(2.6, 2.5, 1.4)}, placeAt(0.6, 0.0, 1.4));
}

Scene roomScene() {
  Scene s;
  s.name = "room";
  s.description = "furnished room: table with objects, chair, cabinet, shelf, bin, balls, crates, pillar";
  addRoom(s);
  // Table 1.2 x 0.8 m, top at 0.775 m, on four thin legs.
  s.add("table_top", box(0.6, 0.4, 0.025), placeAt(2.3, 0.2, 0.75));
  int leg = 0;
  for (double dx : {-0.55, 0.55})
    for (double dy : {-0.35, 0.35})
      s.add("table_leg" + std::to_string(leg++), Cylinder{0.03, 0.3625},
            placeAt(2.3 + dx, 0.2 + dy, 0.3625));
  s.add("book", box(0.15, 0.1, 0.04), placeAt(2.0, 0.35, 0.815, 15.0));
  s.add("vase", Cylinder{0.08, 0.15}, placeAt(2.6, 0.0, 0.925));
  s.add("ball", Sphere{0.12}, placeAt(2.2, -0.05, 0.895));
  // Chair facing the table.
  s.add("chair_seat", box(0.22, 0.22, 0.025), placeAt(1.5, 0.3, 0.45));
  s.add("chair_base", box(0.15, 0.15, 0.21), placeAt(1.5, 0.3, 0.21));
  s.add("chair_back", box(0.025, 0.22, 0.25), placeAt(1.29, 0.3, 0.725));
  // Furniture along the walls.
  s.add("cabinet", box(0.3, 0.45, 0.5), placeAt(2.7, -1.3, 0.5, 20.0));
  s.add("shelf", box(0.2, 0.6, 0.9), placeAt(2.95, 1.2, 0.9));
  s.add("picture", box(0.02, 0.4, 0.3), placeAt(3.18, -0.3, 1.5));
  s.add("bin", Cylinder{0.25, 0.4}, placeAt(2.6, 1.7, 0.4));
  s.add("big_ball", Sphere{0.35}, placeAt(1.0, 1.8, 0.35));
  // The -y side, seen during the pan.
  s.add("crate", box(0.4, 0.25, 0.3), placeAt(1.3, -2.1, 0.3, -10.0));
  s.add("crate_top", box(0.25, 0.25, 0.25), placeAt(1.4, -2.05, 0.85, 25.0));
  s.add("pillar", Cylinder{0.2, 1.4}, placeAt(0.3, -2.2, 1.4));
  s.add("floor_ball", Sphere{0.25}, placeAt(2.4, -2.1, 0.25));
  s.add("bench", box(0.6, 0.2, 0.22), placeAt(-0.8, -2.25, 0.22));
  return s;
}

Scene repeatedScene() {
  Scene s;
  s.name = "repeated";
  s.description = "identical boxes, cylinders and spheres in a near-symmetric grid (one box turned 5 deg, one shifted 5 cm)";
  addRoom(s);
  int n = 0;
  for (double x : {1.0, 1.8, 2.6})
    for (double y : {-0.9, 0.9}) {
      const bool turned = (n == 3);
      const double shift = (n == 4) ? 0.05 : 0.0;
      s.add("box" + std::to_string(n++), box(0.2, 0.2, 0.4), placeAt(x + shift, y, 0.4, turned ? 5.0 : 0.0));
    }
  n = 0;
  for (double x : {1.4, 2.2}) s.add("cylinder" + std::to_string(n++), Cylinder{0.15, 0.5}, placeAt(x, 0.0, 0.5));
  n = 0;
  for (double x : {1.0, 1.8, 2.6}) s.add("sphere" + std::to_string(n++), Sphere{0.2}, placeAt(x, 0.0, 0.2));
  n = 0;
  for (double x : {0.0, 1.0, 2.0}) s.add("wall_box" + std::to_string(n++), box(0.3, 0.3, 0.3), placeAt(x, -2.15, 0.3));
  return s;
}

Scene sparseScene() {
  Scene s;
  s.name = "sparse";
  s.description = "a room with one box, one cylinder and one sphere";
  addRoom(s);
  s.add("box", box(0.4, 0.3, 0.4), placeAt(2.2, 0.3, 0.4, 20.0));
  s.add("cylinder", Cylinder{0.2, 0.6}, placeAt(2.7, -0.8, 0.6));
  s.add("sphere", Sphere{0.3}, placeAt(1.4, -1.9, 0.3));
  return s;
}

Scene planeScene() {
  Scene s;
  s.name = "plane";
  s.description = "degenerate: one 40 x 40 m plane at x = 3 m facing the camera, nothing else";
  s.degenerate = true;
  Isometry3 T = placeAt(3.0, 0.0, 1.4);
  T.linear() = Eigen::AngleAxisd(-EIGEN_PI / 2.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
  s.add("plane", Rectangle{20.0, 20.0}, T);
  return s;
}

/// Two parallel walls along x at y = +-half_width_m, facing each other, centred at (centre_x_m,
/// +-half_width_m, centre_z_m), each half_length_m x half_height_m (half sizes).
void addCorridorWalls(Scene& s, double centre_x_m, double half_width_m, double centre_z_m, double half_length_m,
                      double half_height_m) {
  for (int side : {-1, 1}) {
    Isometry3 T = placeAt(centre_x_m, half_width_m * side, centre_z_m);
    T.linear() = Eigen::AngleAxisd(side * EIGEN_PI / 2.0, Eigen::Vector3d::UnitX()).toRotationMatrix();
    s.add(side < 0 ? "wall_right" : "wall_left", Rectangle{half_length_m, half_height_m}, T);
  }
}

Scene corridorScene() {
  Scene s;
  s.name = "corridor";
  s.description = "degenerate: two parallel walls at y = +-1.2 m along x, nothing else";
  s.degenerate = true;
  addCorridorWalls(s, 5.0, 1.2, 1.4, 20.0, 10.0);
  return s;
}

// ---- Plane-dominated scenes under a hand-held camera (issue 46): where most of the view is one
//      plane, the planar patches cannot fix the directions along it; the few objects decide.

/// A floor (20 x 20 m at z = 0) and a camera held 1.1 m above it, looking down at about 55 deg
/// towards the objects 0.7 m ahead.
Scene floorScene(const std::string& name, int objects) {
  Scene s;
  s.name = name;
  s.degenerate = true;
  s.add("floor", Rectangle{10.0, 10.0}, placeAt(0.0, 0.0, 0.0));
  HandHeldView view;
  view.eye = Eigen::Vector3d(0.0, 0.0, 1.1);
  view.target = Eigen::Vector3d(0.75, 0.0, 0.0);
  s.hand_held = view;
  std::string what;
  // Low objects, in the order they are added: a box, a chair's four legs (its seat out of view),
  // a cable (1 cm: hardly above the depth noise), a book, a bin, a shoe.
  if (objects >= 1) {
    s.add("box", box(0.15, 0.1, 0.075), placeAt(0.75, 0.12, 0.075, 20.0));
    what = "a box";
  }
  if (objects >= 3) {
    int leg = 0;
    for (double dx : {-0.17, 0.17})
      for (double dy : {-0.17, 0.17})
        s.add("chair_leg" + std::to_string(leg++), Cylinder{0.015, 0.22}, placeAt(0.95 + dx, -0.35 + dy, 0.22));
    s.add("cable", box(0.005, 0.6, 0.005), placeAt(0.5, -0.05, 0.005, 35.0));
    what = "a box, a chair's legs, a cable";
  }
  if (objects >= 6) {
    s.add("book", box(0.12, 0.09, 0.02), placeAt(0.45, 0.4, 0.02, -25.0));
    s.add("bin", Cylinder{0.12, 0.15}, placeAt(1.2, 0.35, 0.15));
    s.add("shoe", box(0.14, 0.05, 0.05), placeAt(0.6, -0.45, 0.05, 60.0));
    what += ", a book, a bin, a shoe";
  }
  s.description = "plane-dominated: a floor seen from 1.1 m by a hand-held camera" +
                  (objects == 0 ? std::string(", nothing on it") : ", with " + what);
  return s;
}

/// A wall (x = 2 m) with a door: the wall around the opening, the door leaf 4 cm behind it and
/// a frame standing 2 cm out of it; a floor. The camera is held 1.5 m high, 2 m from the wall.
Scene wallDoorScene() {
  Scene s;
  s.name = "wall_door";
  s.description = "plane-dominated: a wall with a door (frame 2 cm proud, leaf 4 cm recessed) seen by a hand-held camera";
  s.degenerate = true;
  auto facing = [](double x, double y, double z) {  // a Rectangle's +z normal towards -x
    Isometry3 T = placeAt(x, y, z);
    T.linear() = Eigen::AngleAxisd(-EIGEN_PI / 2.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
    return T;
  };
  // Door opening: y in [-0.45, 0.45], z in [0, 2.05]. Rectangle half sizes are (z, y) after the turn.
  s.add("wall_left", Rectangle{1.5, 2.275}, facing(2.0, 2.725, 1.5));
  s.add("wall_right", Rectangle{1.5, 2.275}, facing(2.0, -2.725, 1.5));
  s.add("wall_above", Rectangle{0.475, 0.45}, facing(2.0, 0.0, 2.525));
  s.add("door_leaf", Rectangle{1.025, 0.45}, facing(2.04, 0.0, 1.025));
  s.add("frame_left", box(0.01, 0.03, 1.04), placeAt(1.99, 0.48, 1.04));
  s.add("frame_right", box(0.01, 0.03, 1.04), placeAt(1.99, -0.48, 1.04));
  s.add("frame_top", box(0.01, 0.51, 0.03), placeAt(1.99, 0.0, 2.08));
  s.add("floor", Rectangle{10.0, 10.0}, placeAt(0.0, 0.0, 0.0));
  HandHeldView view;
  view.eye = Eigen::Vector3d(0.0, 0.0, 1.5);
  view.target = Eigen::Vector3d(2.0, 0.0, 1.4);
  s.hand_held = view;
  return s;
}

/// A corridor 2 m wide (walls at y = +-1 m), with a floor, walked along +x at 0.3 m/s.
Scene corridorWalkScene() {
  Scene s;
  s.name = "corridor_walk";
  s.description = "plane-dominated: a corridor 2 m wide with a floor, walked along by a hand-held camera";
  s.degenerate = true;
  addCorridorWalls(s, 10.0, 1.0, 1.5, 20.0, 1.5);
  s.add("floor", Rectangle{20.0, 1.0}, placeAt(10.0, 0.0, 0.0));
  HandHeldView view;
  view.eye = Eigen::Vector3d(0.0, 0.0, 1.4);
  view.target = Eigen::Vector3d(3.0, 0.0, 1.0);
  view.sweep_m = 0.1;
  view.look_sweep_m = 0.3;
  view.drift_mps = Eigen::Vector3d(0.3, 0.0, 0.0);
  s.hand_held = view;
  return s;
}

/// A table (1.2 x 0.8 m, top at 0.75 m, four legs) on a floor, seen from 0.85 m above its top.
Scene tableTopScene() {
  Scene s;
  s.name = "table_top";
  s.description = "plane-dominated: a table top seen from above by a hand-held camera, the floor around it";
  s.degenerate = true;
  s.add("floor", Rectangle{10.0, 10.0}, placeAt(0.0, 0.0, 0.0));
  s.add("table_top", box(0.6, 0.4, 0.025), placeAt(0.6, 0.0, 0.725));
  int leg = 0;
  for (double dx : {-0.55, 0.55})
    for (double dy : {-0.35, 0.35})
      s.add("table_leg" + std::to_string(leg++), Cylinder{0.03, 0.35}, placeAt(0.6 + dx, dy, 0.35));
  HandHeldView view;
  view.eye = Eigen::Vector3d(0.0, 0.0, 1.6);
  view.target = Eigen::Vector3d(0.6, 0.0, 0.75);
  view.sweep_m = 0.2;
  view.look_sweep_m = 0.15;
  s.hand_held = view;
  return s;
}

/// A wall 10 cm thick and `height` high on the floor, from (x0, y0) to (x1, y1) along x or y.
void addWall(Scene& s, const std::string& name, double x0, double y0, double x1, double y1, double height) {
  const double hx = x0 == x1 ? 0.05 : std::abs(x1 - x0) / 2, hy = y0 == y1 ? 0.05 : std::abs(y1 - y0) / 2;
  s.add(name, box(hx, hy, height / 2), placeAt((x0 + x1) / 2, (y0 + y1) / 2, height / 2));
}

/// Two furnished rooms, A (x in [0, 6], y in [0, 5]) and B (x in [14, 20]), joined by two
/// corridors 1.2 m wide (north: y in [3.4, 4.6]; south: y in [0.4, 1.6]), 2.6 m high. The walk
/// goes once around: from A through the north corridor into B, round B, back through the south
/// corridor into A, and ends where it began (34 m). The rooms hold different furniture and
/// each corridor a few objects of its own, so that every place can be told from the others and
/// tracked (a bare corridor is degenerate along its axis).
Scene twoRoomsScene() {
  Scene s;
  s.name = "two_rooms";
  s.description = "two furnished rooms joined by two corridors, walked around once (a 34 m loop)";
  const double h = 2.6;
  s.add("floor", Rectangle{10.0, 2.5}, placeAt(10.0, 2.5, 0.0));
  s.add("ceiling", Rectangle{10.0, 2.5}, placeAt(10.0, 2.5, h));
  // Room A and room B: outer walls, and the wall towards the corridors with two doorways each.
  for (const auto& [room, x_out, x_in] : {std::tuple{"a", 0.0, 6.0}, std::tuple{"b", 20.0, 14.0}}) {
    const std::string r = room;
    addWall(s, "wall_" + r + "_end", x_out, 0.0, x_out, 5.0, h);
    addWall(s, "wall_" + r + "_south", std::min(x_out, x_in), 0.0, std::max(x_out, x_in), 0.0, h);
    addWall(s, "wall_" + r + "_north", std::min(x_out, x_in), 5.0, std::max(x_out, x_in), 5.0, h);
    addWall(s, "wall_" + r + "_door_0", x_in, 0.0, x_in, 0.4, h);
    addWall(s, "wall_" + r + "_door_1", x_in, 1.6, x_in, 3.4, h);
    addWall(s, "wall_" + r + "_door_2", x_in, 4.6, x_in, 5.0, h);
  }
  for (const auto& [corridor, y0, y1] : {std::tuple{"north", 3.4, 4.6}, std::tuple{"south", 0.4, 1.6}}) {
    addWall(s, std::string("corridor_") + corridor + "_0", 6.0, y0, 14.0, y0, h);
    addWall(s, std::string("corridor_") + corridor + "_1", 6.0, y1, 14.0, y1, h);
  }
  // Room A: a table with things on it, a chair, a shelf, a bin, a ball, a cabinet, a picture.
  s.add("a_table_top", box(0.6, 0.4, 0.025), placeAt(3.2, 2.4, 0.75));
  int leg = 0;
  for (double dx : {-0.55, 0.55})
    for (double dy : {-0.35, 0.35})
      s.add("a_table_leg" + std::to_string(leg++), Cylinder{0.03, 0.3625}, placeAt(3.2 + dx, 2.4 + dy, 0.3625));
  s.add("a_book", box(0.15, 0.1, 0.04), placeAt(3.0, 2.5, 0.815, 15.0));
  s.add("a_vase", Cylinder{0.08, 0.15}, placeAt(3.5, 2.2, 0.925));
  s.add("a_chair_seat", box(0.22, 0.22, 0.025), placeAt(2.3, 2.6, 0.45));
  s.add("a_chair_base", box(0.15, 0.15, 0.21), placeAt(2.3, 2.6, 0.21));
  s.add("a_chair_back", box(0.025, 0.22, 0.25), placeAt(2.09, 2.6, 0.725));
  s.add("a_shelf", box(0.2, 0.6, 0.9), placeAt(0.3, 1.3, 0.9));
  s.add("a_bin", Cylinder{0.25, 0.4}, placeAt(5.4, 2.5, 0.4));
  s.add("a_ball", Sphere{0.35}, placeAt(1.2, 4.3, 0.35));
  s.add("a_cabinet", box(0.3, 0.45, 0.5), placeAt(5.3, 0.55, 0.5, 20.0));
  s.add("a_picture", box(0.02, 0.4, 0.3), placeAt(0.07, 3.3, 1.5));
  s.add("a_crate", box(0.3, 0.25, 0.25), placeAt(3.5, 4.6, 0.25, -15.0));
  // Room B: a sofa, a pillar, a round table, a floor lamp, stacked crates, a low box.
  s.add("b_sofa_seat", box(0.45, 1.0, 0.22), placeAt(19.4, 2.5, 0.22));
  s.add("b_sofa_back", box(0.12, 1.0, 0.4), placeAt(19.8, 2.5, 0.6));
  s.add("b_pillar", Cylinder{0.25, 1.3}, placeAt(17.6, 4.1, 1.3));
  s.add("b_round_table", Cylinder{0.45, 0.02}, placeAt(18.2, 1.0, 0.72));
  s.add("b_round_table_foot", Cylinder{0.05, 0.35}, placeAt(18.2, 1.0, 0.35));
  s.add("b_lamp_pole", Cylinder{0.03, 0.8}, placeAt(15.0, 4.5, 0.8));
  s.add("b_lamp_shade", Sphere{0.2}, placeAt(15.0, 4.5, 1.7));
  s.add("b_crate", box(0.35, 0.3, 0.3), placeAt(16.2, 0.5, 0.3, 10.0));
  s.add("b_crate_top", box(0.25, 0.2, 0.2), placeAt(16.3, 0.55, 0.8, -20.0));
  s.add("b_low_box", box(0.5, 0.3, 0.15), placeAt(18.9, 4.5, 0.15, 5.0));
  s.add("b_ball", Sphere{0.25}, placeAt(15.5, 2.0, 0.25));
  // The corridors: a few objects each, on both sides.
  s.add("north_bench", box(0.5, 0.15, 0.22), placeAt(7.6, 4.42, 0.22));
  s.add("north_extinguisher", Cylinder{0.08, 0.3}, placeAt(9.3, 3.55, 0.5));
  s.add("north_cabinet", box(0.35, 0.12, 0.6), placeAt(11.0, 4.45, 0.6));
  s.add("north_plant", Cylinder{0.18, 0.25}, placeAt(12.8, 3.62, 0.25));
  s.add("north_plant_top", Sphere{0.25}, placeAt(12.8, 3.62, 0.75));
  s.add("south_radiator", box(0.5, 0.05, 0.3), placeAt(7.4, 0.48, 0.5));
  s.add("south_box", box(0.25, 0.2, 0.25), placeAt(9.0, 1.38, 0.25, 10.0));
  s.add("south_ball", Sphere{0.2}, placeAt(10.6, 0.65, 0.2));
  s.add("south_shelf", box(0.4, 0.12, 0.5), placeAt(12.3, 1.45, 0.5));
  s.add("south_post", Cylinder{0.06, 0.55}, placeAt(13.4, 0.6, 0.55));
  // The walk, at eye height, looking slightly down.
  s.walk = {
      {{1.5, 2.5, 1.4}, {5.0, 2.2, 0.9}, "room_a"},
      {{3.5, 3.8, 1.4}, {6.5, 4.0, 1.0}, "to_north_door"},
      {{5.5, 4.0, 1.4}, {10.0, 4.0, 1.1}, "corridor_north"},
      {{13.5, 4.0, 1.4}, {18.0, 4.0, 1.0}, "into_room_b"},
      {{16.0, 3.9, 1.4}, {19.0, 2.5, 0.9}, "room_b"},
      {{17.5, 2.0, 1.4}, {15.0, 0.5, 0.9}, "to_south_door"},
      {{14.5, 1.0, 1.4}, {10.0, 1.0, 1.1}, "corridor_south"},
      {{6.5, 1.0, 1.4}, {2.0, 1.0, 1.0}, "into_room_a"},
      {{4.0, 1.6, 1.4}, {2.0, 3.5, 0.9}, "back_to_start"},
      {{1.5, 2.5, 1.4}, {5.0, 2.2, 0.9}, ""},
  };
  return s;
}

/// An outdoor street for a rotating LiDAR (issue 49): the ground, building facades of different
/// heights, depths and setbacks on both sides with gaps between them, parked cars, street lights
/// every 10 m (a repeated structure), trees and a bus shelter; walked along 34 m at a car-roof
/// LiDAR's height, through a U-turn across the street, and 16 m back on the other side.
Scene streetScene() {
  Scene s;
  s.name = "street";
  s.description = "an outdoor street: facades, ground, street lights, trees and cars, walked 34 m, a U-turn, 16 m back";
  s.add("ground", Rectangle{35.0, 20.0}, placeAt(20.0, 0.0, 0.0));
  // Buildings: (x from, x to, depth, height, setback from the street's edge at |y| = 8).
  struct Building {
    double x0, x1, depth, height, setback;
  };
  const Building north[] = {{-4, 7, 8, 12, 0.0}, {9, 17, 6, 7, 1.5}, {17, 26, 10, 15, 0.0}, {29, 37, 7, 9, 0.8},
                            {37, 46, 9, 11, 0.0}};
  const Building south[] = {{-6, 4, 7, 8, 0.5}, {4, 15, 9, 13, 0.0}, {18, 24, 6, 6, 2.0}, {24, 33, 8, 10, 0.0},
                            {35, 45, 7, 14, 1.0}};
  int n = 0;
  for (const auto* side : {north, south}) {
    const double sign = side == north ? 1.0 : -1.0;
    for (int k = 0; k < 5; ++k) {
      const Building& b = side[k];
      const double y = sign * (8.0 + b.setback + 0.5 * b.depth);
      s.add("building" + std::to_string(n++), box(0.5 * (b.x1 - b.x0), 0.5 * b.depth, 0.5 * b.height),
            placeAt(0.5 * (b.x0 + b.x1), y, 0.5 * b.height));
    }
  }
  // Street lights every 10 m on both sidewalks, staggered by 5 m.
  for (int k = 0; k < 5; ++k) {
    s.add("light_n" + std::to_string(k), Cylinder{0.09, 3.0}, placeAt(10.0 * k, 6.5, 3.0));
    s.add("light_s" + std::to_string(k), Cylinder{0.09, 3.0}, placeAt(5.0 + 10.0 * k, -6.5, 3.0));
  }
  // Parked cars (a body and a cabin), trees (a trunk and a crown), a bus shelter, a kiosk.
  const std::pair<double, double> cars[] = {{3.0, 4.6}, {12.5, 4.6}, {27.0, 4.6}, {8.0, -4.6}, {21.0, -4.6}, {34.0, -4.6}};
  n = 0;
  for (const auto& [x, y] : cars) {
    s.add("car" + std::to_string(n) + "_body", box(2.2, 0.9, 0.45), placeAt(x, y, 0.6));
    s.add("car" + std::to_string(n++) + "_cabin", box(1.2, 0.8, 0.35), placeAt(x - 0.3, y, 1.4));
  }
  const std::pair<double, double> trees[] = {{6.0, -6.8}, {19.0, 6.8}, {31.0, -6.8}, {40.0, 6.8}};
  n = 0;
  for (const auto& [x, y] : trees) {
    s.add("tree" + std::to_string(n) + "_trunk", Cylinder{0.18, 1.5}, placeAt(x, y, 1.5));
    s.add("tree" + std::to_string(n++) + "_crown", Sphere{1.6}, placeAt(x, y, 4.2));
  }
  s.add("shelter_roof", box(2.0, 0.8, 0.05), placeAt(15.0, -6.6, 2.5));
  s.add("shelter_back", box(2.0, 0.04, 1.2), placeAt(15.0, -7.35, 1.3));
  s.add("kiosk", box(1.2, 1.0, 1.3), placeAt(24.0, 7.0, 1.3, 15.0));
  // The walk, at 1.8 m, looking ahead level.
  s.walk = {
      {{2.0, -1.5, 1.8}, {12.0, -1.5, 1.8}, "street_east"},
      {{36.0, -1.5, 1.8}, {46.0, -1.5, 1.8}, "u_turn"},
      {{39.0, 0.0, 1.8}, {39.0, 10.0, 1.8}, "u_turn_end"},
      {{36.0, 1.5, 1.8}, {26.0, 1.5, 1.8}, "street_west"},
      {{20.0, 1.5, 1.8}, {10.0, 1.5, 1.8}, ""},
  };
  return s;
}

}  // namespace

std::vector<std::string> sceneNames() {
  return {"room",    "repeated", "sparse",  "plane",     "corridor",      "floor_0",
          "floor_1", "floor_3",  "floor_6", "wall_door", "corridor_walk", "table_top", "two_rooms", "street"};
}

Scene makeScene(const std::string& name) {
  if (name == "room") return roomScene();
  if (name == "repeated") return repeatedScene();
  if (name == "sparse") return sparseScene();
  if (name == "plane") return planeScene();
  if (name == "corridor") return corridorScene();
  for (int objects : {0, 1, 3, 6})
    if (name == "floor_" + std::to_string(objects)) return floorScene(name, objects);
  if (name == "wall_door") return wallDoorScene();
  if (name == "corridor_walk") return corridorWalkScene();
  if (name == "table_top") return tableTopScene();
  if (name == "two_rooms") return twoRoomsScene();
  if (name == "street") return streetScene();
  std::string valid;
  for (const auto& n : sceneNames()) valid += (valid.empty() ? "" : ", ") + n;
  throw Error("unknown scene '" + name + "'; valid scenes: " + valid);
}

}  // namespace gasp::sim
