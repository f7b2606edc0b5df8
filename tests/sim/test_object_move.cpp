// Moved objects (object_move.h): parsing the program's form, the scene before and after the move,
// and the rendered frames (the object is where the move puts it, the rest of the room unchanged).
#include <gtest/gtest.h>

#include <string>

#include "gasp/core/error.h"
#include "gasp/sim/object_move.h"
#include "gasp/sim/simulation.h"

namespace {

using namespace gasp::sim;

/// Pixels of frame i whose ground-truth surface belongs to an object whose name starts with `prefix`.
int pixelsOf(const Simulation& sim, int i, const std::string& prefix) {
  const RenderedFrame f = sim.render(i);
  int n = 0;
  for (int v = 0; v < f.surface_id.rows; ++v)
    for (int u = 0; u < f.surface_id.cols; ++u) {
      const SceneObject* o = sim.scene().objectOfSurface(f.surface_id.at<std::uint16_t>(v, u));
      if (o && o->name.rfind(prefix, 0) == 0) ++n;
    }
  return n;
}

}  // namespace

TEST(ObjectMove, ParsesTheProgramsForm) {
  ObjectMove m = parseObjectMove("chair:0,-0.6,0@30");
  EXPECT_EQ(m.prefix, "chair");
  EXPECT_TRUE(m.shift_m.isApprox(Eigen::Vector3d(0, -0.6, 0)));
  EXPECT_EQ(m.yaw_deg, 0.0);
  EXPECT_EQ(m.at_frame, 30);
  m = parseObjectMove("table:0.1,0.2,0,45@7");
  EXPECT_EQ(m.prefix, "table");
  EXPECT_EQ(m.yaw_deg, 45.0);
  EXPECT_EQ(m.at_frame, 7);
  for (const char* bad : {"", "chair", ":0,0,0@3", "chair:0,0@3", "chair:0,0,0,0,0@3", "chair:0,x,0@3",
                          "chair:0,0,0", "chair:0,0,0@", "chair:0,0,0@3.5", "chair:0,nan,0@3", "chair:0,0,0@x",
                          "chair:0,0,0,@3", "chair:,0,0,0@3", "chair: 0,0,0@3", "chair:0,0,0 @3", "chair:0,,0@3", "chair:0,0,0@ 3", "chair:0,0,0@-3"}) {
    try {
      parseObjectMove(bad);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const gasp::Error& e) {
      EXPECT_NE(std::string(e.what()).find("PREFIX:DX,DY,DZ@FRAME"), std::string::npos) << e.what();
    }
  }
}

TEST(ObjectMove, TheObjectIsAtItsPlaceBeforeTheFrameAndMovedFromItOn) {
  Scene s = makeScene("room");
  const std::size_t before = s.objects.size();
  const Eigen::Vector3d seat = s.object("chair_seat").T_world_object.translation();
  applyObjectMoves(s, {ObjectMove{"chair", Eigen::Vector3d(0.0, -0.6, 0.0), 90.0, 5}}, 20);
  ASSERT_EQ(s.objects.size(), before + 3);  // seat, base, back
  const SceneObject& old_seat = s.object("chair_seat");
  const SceneObject& new_seat = s.object("chair_seat@moved");
  EXPECT_TRUE(old_seat.visibleAt(4));
  EXPECT_FALSE(old_seat.visibleAt(5));
  EXPECT_FALSE(new_seat.visibleAt(4));
  EXPECT_TRUE(new_seat.visibleAt(5));
  EXPECT_NE(new_seat.first_surface_id, old_seat.first_surface_id);
  // Turned about the vertical through the parts' mean origin (the back is off-centre), then shifted.
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const char* part : {"chair_seat", "chair_base", "chair_back"}) centre += s.object(part).T_world_object.translation();
  centre /= 3.0;
  centre.z() = 0.0;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(EIGEN_PI / 2.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  for (const char* part : {"chair_seat", "chair_base", "chair_back"}) {
    const gasp::Isometry3& T0 = s.object(part).T_world_object;
    const gasp::Isometry3& T1 = s.object(std::string(part) + "@moved").T_world_object;
    EXPECT_TRUE(T1.translation().isApprox(centre + R * (T0.translation() - centre) + Eigen::Vector3d(0, -0.6, 0), 1e-12))
        << part;
    EXPECT_TRUE(T1.linear().isApprox(R * T0.linear(), 1e-12)) << part;
  }
  EXPECT_TRUE(old_seat.T_world_object.translation().isApprox(seat));
}

TEST(ObjectMove, RenderedFramesShowTheMove) {
  SimulationOptions o;
  o.noise = KinectNoiseModel::exact();
  const Simulation still(o);
  o.moves = {parseObjectMove("chair:0,-0.6,0@6")};
  const Simulation moved(o);
  // Before the move the frames are the same; from it on the chair is elsewhere and no old part is seen.
  const RenderedFrame a = still.render(5), b = moved.render(5);
  EXPECT_EQ(cv::countNonZero(a.depth != b.depth), 0);
  EXPECT_GT(pixelsOf(moved, 5, "chair"), 1000);
  EXPECT_EQ(pixelsOf(moved, 5, "chair_seat@"), 0);
  const RenderedFrame c = still.render(6), d = moved.render(6);
  EXPECT_GT(cv::countNonZero(c.depth != d.depth), 1000);
  int old_parts = 0;
  for (const char* part : {"chair_seat", "chair_base", "chair_back"})
    old_parts += pixelsOf(moved, 6, std::string(part)) - pixelsOf(moved, 6, std::string(part) + "@");
  EXPECT_EQ(old_parts, 0);
  EXPECT_GT(pixelsOf(moved, 6, "chair_seat@moved"), 100);
}

TEST(ObjectMove, BadMovesThrow) {
  const auto throwsWith = [](const std::vector<ObjectMove>& moves, const std::string& text) {
    Scene s = makeScene("room");
    try {
      applyObjectMoves(s, moves, 20);
      ADD_FAILURE() << "no error, expected: " << text;
    } catch (const gasp::Error& e) {
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
  };
  throwsWith({ObjectMove{"sofa", Eigen::Vector3d::Zero(), 0.0, 3}}, "no object whose name starts with 'sofa'");
  throwsWith({ObjectMove{"chair", Eigen::Vector3d::Zero(), 0.0, 0}}, "outside [1, 19]");
  throwsWith({ObjectMove{"chair", Eigen::Vector3d::Zero(), 0.0, 20}}, "outside [1, 19]");
  throwsWith({ObjectMove{"chair", Eigen::Vector3d(NAN, 0, 0), 0.0, 3}}, "finite");
  throwsWith({ObjectMove{"chair", Eigen::Vector3d::Zero(), 0.0, 3}, ObjectMove{"chair_back", Eigen::Vector3d::Zero(), 0.0, 5}},
             "moved by two moves");
  throwsWith({ObjectMove{"", Eigen::Vector3d::Zero(), 0.0, 3}}, "empty object name prefix");
  // The occluder appears midway along the path: a move before that would move nothing.
  SimulationOptions early;
  early.moves = {ObjectMove{"occluder", Eigen::Vector3d(0.0, 0.8, 0.0), 0.0, 20}};
  try {
    Simulation{early};
    ADD_FAILURE() << "a move before the occluder appears was accepted";
  } catch (const gasp::Error& e) {
    EXPECT_NE(std::string(e.what()).find("would move nothing"), std::string::npos) << e.what();
  }
  early.moves[0].at_frame = 52;
  EXPECT_NO_THROW(Simulation{early});
  SimulationOptions o;
  o.moves = {ObjectMove{"sofa", Eigen::Vector3d::Zero(), 0.0, 3}};
  EXPECT_THROW(Simulation{o}, gasp::Error);
}
