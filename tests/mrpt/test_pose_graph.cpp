// toPoseGraph (pose_graph.h): GASP's odometry as MRPT's CNetworkOfPoses3DInf.
#include <gtest/gtest.h>

#include <mrpt/poses/CPose3D.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/mrpt/pose_graph.h"
#include "gasp/rawlog/observation_conversion.h"
#include "gasp_test_data.h"

namespace {

using gasp::Isometry3;

Isometry3 pose(double x, double y, double z, double angle_deg, const Eigen::Vector3d& axis) {
  Isometry3 T = Isometry3::Identity();
  T.linear() = Eigen::AngleAxisd(angle_deg * M_PI / 180.0, axis.normalized()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, y, z);
  return T;
}

/// An MRPT-like mounting: camera 0.2 m up, optical z along the robot's x.
Isometry3 mountedCamera() {
  Isometry3 T_robot_camera = Isometry3::Identity();
  T_robot_camera.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  T_robot_camera.translation() = Eigen::Vector3d(0.05, 0, 0.2);
  return T_robot_camera;
}

/// Three frames, frames 1 and 2 registered to keyframe 0.
struct Odometry {
  std::vector<gasp::OdometryFrame> frames;
  std::vector<gasp::PoseConstraint> constraints;
};

Odometry threeFrames() {
  Odometry o;
  const Isometry3 poses[3] = {pose(0, 0, 0, 0, Eigen::Vector3d::UnitX()), pose(0.1, 0.02, 0.3, 20, Eigen::Vector3d(0, 1, 0.2)),
                              pose(-0.2, 0.05, 0.5, 35, Eigen::Vector3d(0.3, 1, -0.1))};
  for (std::size_t i = 0; i < 3; ++i) {
    gasp::OdometryFrame f;
    f.index = i;
    f.timestamp = 10.0 + 0.1 * static_cast<double>(i);
    f.T_world_camera = poses[i];
    f.tracked = true;
    o.frames.push_back(f);
  }
  // An anisotropic, correlated covariance (1-2 cm, 0.5-2 deg), so that the frame change matters.
  gasp::Matrix6d cov = gasp::Matrix6d::Zero();
  const double deg = M_PI / 180.0;
  cov.diagonal() << 1e-4, 4e-4, 2.25e-4, std::pow(1 * deg, 2), std::pow(2 * deg, 2), std::pow(0.5 * deg, 2);
  gasp::Matrix6d mix = gasp::Matrix6d::Identity();
  mix(0, 4) = 0.3, mix(1, 3) = -0.2, mix(2, 0) = 0.4, mix(5, 1) = 0.5, mix(3, 4) = 0.3;
  const gasp::Matrix6d info = (mix * cov * mix.transpose()).inverse();
  for (auto [from, to] : {std::pair<std::size_t, std::size_t>{0, 1}, {0, 2}}) {
    gasp::PoseConstraint c;
    c.from = from, c.to = to;
    c.T_from_to = poses[from].inverse() * poses[to];
    c.information = info;
    o.constraints.push_back(c);
  }
  return o;
}

}  // namespace

TEST(PoseGraph, NodesAndEdgesAreTheOdometrysInTheRobotFrame) {
  const Odometry o = threeFrames();
  const Isometry3 T_robot_camera = mountedCamera();
  const auto g = gasp::toPoseGraph(o.frames, o.constraints, T_robot_camera);
  EXPECT_EQ(g.skipped_constraints, 0u);
  ASSERT_EQ(g.graph.nodes.size(), 3u);
  ASSERT_EQ(g.graph.edgeCount(), 2u);
  EXPECT_EQ(g.graph.root, 0u);
  for (std::size_t i = 0; i < 3; ++i)
    EXPECT_TRUE(gasp::fromCPose3D(g.graph.nodes.at(i)).isApprox(o.frames[i].T_world_camera * T_robot_camera.inverse(), 1e-9));
  for (const auto& [ids, edge] : g.graph.edges) {
    // MRPT's convention: node_to = node_from (+) edge.
    const mrpt::poses::CPose3D composed = g.graph.nodes.at(ids.first) + edge.mean;
    EXPECT_TRUE(gasp::fromCPose3D(composed).isApprox(gasp::fromCPose3D(g.graph.nodes.at(ids.second)), 1e-9)) << ids.first << "->" << ids.second;
  }
}

TEST(PoseGraph, TheEdgeCovarianceIsTheSampledOneInMrptsCoordinates) {
  // Independent of pose_covariance.h's algebra: perturb the camera-frame constraint by draws from
  // its information (left perturbation in frame `from`), carry each draw to the robot frames and
  // into MRPT's [x y z yaw pitch roll], and compare the sample covariance with the edge's.
  const Odometry o = threeFrames();
  const Isometry3 T_robot_camera = mountedCamera();
  const auto g = gasp::toPoseGraph(o.frames, o.constraints, T_robot_camera);
  const auto& c = o.constraints[1];
  const Eigen::Matrix<double, 6, 6> L = c.information.inverse().llt().matrixL();
  std::mt19937 rng(7);
  std::normal_distribution<double> n01;
  const int n = 20000;
  std::vector<Eigen::Matrix<double, 6, 1>> draws;
  Eigen::Matrix<double, 6, 1> mean = Eigen::Matrix<double, 6, 1>::Zero();
  for (int i = 0; i < n; ++i) {
    Eigen::Matrix<double, 6, 1> z;
    for (int k = 0; k < 6; ++k) z[k] = n01(rng);
    const Eigen::Matrix<double, 6, 1> xi = L * z;
    Isometry3 E = Isometry3::Identity();
    E.linear() = Eigen::AngleAxisd(xi.tail<3>().norm(), xi.tail<3>().normalized()).toRotationMatrix();
    E.translation() = xi.head<3>();
    const Isometry3 T = T_robot_camera * (E * c.T_from_to) * T_robot_camera.inverse();
    const mrpt::poses::CPose3D p = gasp::toCPose3D(T);
    Eigen::Matrix<double, 6, 1> v;
    v << p.x(), p.y(), p.z(), p.yaw(), p.pitch(), p.roll();
    draws.push_back(v);
    mean += v / n;
  }
  Eigen::Matrix<double, 6, 6> sample = Eigen::Matrix<double, 6, 6>::Zero();
  for (const auto& v : draws) sample += (v - mean) * (v - mean).transpose() / (n - 1);
  const Eigen::Matrix<double, 6, 6> edge_cov = g.graph.getEdge(0, 2).cov_inv.asEigen().inverse();
  for (int r = 0; r < 6; ++r)
    for (int k = 0; k < 6; ++k)
      EXPECT_NEAR(sample(r, k), edge_cov(r, k), 0.03 * std::sqrt(edge_cov(r, r) * edge_cov(k, k))) << r << "," << k;
}

TEST(PoseGraph, AConstraintWithoutACovarianceIsLeftOutAndCounted) {
  Odometry o = threeFrames();
  o.constraints[1].information(5, 5) = 0.0;  // one direction unobservable
  const auto g = gasp::toPoseGraph(o.frames, o.constraints);
  EXPECT_EQ(g.skipped_constraints, 1u);
  EXPECT_EQ(g.graph.edgeCount(), 1u);
  o.constraints[0].to = 7;
  try {
    gasp::toPoseGraph(o.frames, o.constraints);
    ADD_FAILURE() << "no error";
  } catch (const gasp::Error& e) {
    EXPECT_NE(std::string(e.what()).find("frame 7 of 3"), std::string::npos) << e.what();
  }
}

TEST(PoseGraph, ItsTextFileLoadsBackIntoMrpt) {
  const Odometry o = threeFrames();
  const auto g = gasp::toPoseGraph(o.frames, o.constraints);
  const std::string path = gasp::test::scratchDir() + "/odometry.graph";
  g.graph.saveToTextFile(path);
  mrpt::graphs::CNetworkOfPoses3DInf loaded;
  loaded.loadFromTextFile(path);
  ASSERT_EQ(loaded.nodes.size(), 3u);
  ASSERT_EQ(loaded.edgeCount(), 2u);
  for (const auto& [ids, edge] : g.graph.edges) {
    const auto& back = loaded.getEdge(ids.first, ids.second);
    EXPECT_TRUE(gasp::fromCPose3D(back.mean).isApprox(gasp::fromCPose3D(edge.mean), 1e-5));
    // MRPT 2.5's reader drops the information's yaw-pitch-roll cross terms: it reads them into
    // the lower triangle, then mirrors the upper triangle over it. Every other entry survives.
    for (int r = 0; r < 6; ++r)
      for (int k = 0; k < 6; ++k)
        if (r < 3 || k < 3 || r == k) {
          EXPECT_NEAR(back.cov_inv(r, k), edge.cov_inv(r, k), 1e-4 * std::abs(edge.cov_inv(r, r))) << r << "," << k;
        }
  }
}

TEST(PoseGraph, AnEdgeConvertsBackToTheConstraintItCameFrom) {
  // Camera frames on two different mountings; a random pose and a random positive definite
  // information: edgeFromConstraint() then constraintFromEdge() gives them back (first order
  // conversions, exact inverses of each other up to the Jacobian's differences).
  std::mt19937 rng(11);
  std::normal_distribution<double> g(0.0, 1.0);
  const Isometry3 S_from = mountedCamera();
  const Isometry3 S_to = pose(0.1, -0.05, 0.3, 20.0, Eigen::Vector3d(1, 2, 3).normalized()) * mountedCamera();
  for (int trial = 0; trial < 20; ++trial) {
    gasp::PoseConstraint c;
    c.from = 3;
    c.to = 9;
    c.T_from_to = pose(g(rng), g(rng), g(rng), 40.0 * g(rng), Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized());
    Eigen::Matrix<double, 6, 6> A;
    for (int r = 0; r < 6; ++r)
      for (int k = 0; k < 6; ++k) A(r, k) = g(rng);
    c.information = A * A.transpose() + 10.0 * Eigen::Matrix<double, 6, 6>::Identity();
    const auto edge = gasp::edgeFromConstraint(c, S_from, S_to);
    ASSERT_TRUE(edge.has_value());
    // The edge is the pose between the robot frames.
    EXPECT_TRUE(gasp::fromCPose3D(edge->mean).isApprox(S_from * c.T_from_to * S_to.inverse(), 1e-9));
    const auto back = gasp::constraintFromEdge(c.from, c.to, *edge, S_from, S_to);
    ASSERT_TRUE(back.has_value());
    EXPECT_EQ(back->from, 3u);
    EXPECT_EQ(back->to, 9u);
    EXPECT_TRUE(back->T_from_to.isApprox(c.T_from_to, 1e-9));
    EXPECT_LT((back->information - c.information).norm(), 1e-5 * c.information.norm()) << "trial " << trial;
  }
}

TEST(PoseGraph, AnEdgeWithoutAPositiveDefiniteInformationGivesNoConstraint) {
  mrpt::poses::CPose3DPDFGaussianInf edge;
  edge.cov_inv.setZero();
  EXPECT_FALSE(gasp::constraintFromEdge(0, 1, edge, Isometry3::Identity(), Isometry3::Identity()).has_value());
  edge.cov_inv.setIdentity();
  edge.cov_inv(2, 2) = std::nan("");
  EXPECT_FALSE(gasp::constraintFromEdge(0, 1, edge, Isometry3::Identity(), Isometry3::Identity()).has_value());
  edge.cov_inv.setIdentity();
  edge.cov_inv(5, 5) = -1.0;
  EXPECT_FALSE(gasp::constraintFromEdge(0, 1, edge, Isometry3::Identity(), Isometry3::Identity()).has_value());
}
