// A rotating LiDAR's sweep given as a point cloud (mrpt::obs::CObservationPointCloud): its rings
// and columns found from the points (gasp/core/range_scan.h rangeScanFromPoints(), the rawlog's
// rangeScanFrom()), on the simulator's sweeps and on MRPT's real VLP-16 sample.
#include <gtest/gtest.h>

#include <mrpt/core/Clock.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/obs/CObservationVelodyneScan.h>
#include <mrpt/serialization/CArchive.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/core/range_scan.h"
#include "gasp/pipeline/range_view.h"
#include "gasp/rawlog/depth_sequence.h"
#include "gasp/rawlog/observation_conversion.h"
#include "gasp/rawlog/range_scan.h"
#include "gasp/sim/lidar.h"
#include "gasp/sim/scene.h"
#include "gasp_test_data.h"
#include "program_run.h"

namespace {

constexpr const char* kVelodyne = "/usr/share/mrpt/datasets/test_velodyne_VLP16.rawlog";

/// Raw points as a point cloud (the bad inputs below).
mrpt::obs::CObservationPointCloud cloudOf(const std::vector<Eigen::Vector3d>& points, const std::string& label) {
  mrpt::obs::CObservationPointCloud cloud;
  cloud.sensorLabel = label;
  auto map = mrpt::maps::CSimplePointsMap::Create();
  for (const Eigen::Vector3d& p : points)
    map->insertPoint(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()));
  cloud.pointcloud = map;
  return cloud;
}

/// Every frame of a rawlog read for sweeps (DepthSequenceOptions::sweeps).
std::vector<gasp::RgbdFrame> sweepsOf(const std::string& rawlog) {
  gasp::DepthSequenceOptions o;
  o.rawlog_path = rawlog;
  o.sweeps = true;
  gasp::DepthSequence sequence(o);
  std::vector<gasp::RgbdFrame> frames;
  while (auto f = sequence.next()) frames.push_back(std::move(*f));
  return frames;
}

/// The largest distance from one of `a`'s points to the nearest of `b`'s (the first `n` of a).
double worstNearest(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b, std::size_t n) {
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size() && i < n; ++i) {
    double nearest = 1e18;
    for (const Eigen::Vector3d& q : b) nearest = std::min(nearest, (a[i] - q).squaredNorm());
    worst = std::max(worst, nearest);
  }
  return std::sqrt(worst);
}

gasp::Isometry3 motion(double x, double y, double yaw_deg) {
  gasp::Isometry3 T = gasp::Isometry3::Identity();
  T.linear() = Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, y, 0.0);
  return T;
}

}  // namespace

// A sweep stored as a 3D range scan of its points alone (toPointsScan(), what gasp-slam
// --simplemap-points writes for MRPT's points maps): written, read back through MRPT's
// serialization, it is a sweep, read as its point cloud is, with its mounting and time.
TEST(PointCloudSweep, ASweepAsA3DScanOfPointsReadsBackAsItsPointCloud) {
  gasp::Isometry3 T = gasp::Isometry3::Identity();
  T.translation() = Eigen::Vector3d(0.5, 0.0, 1.0);
  gasp::RangeScan scan = gasp::sim::simulateLidarScan(gasp::sim::makeScene("room"), gasp::sim::lidarSensor(16), T, 3, 0);
  scan.timestamp = 1234.5;
  scan.T_robot_sensor.translation() = Eigen::Vector3d(0.1, 0.0, 0.8);
  const mrpt::obs::CObservation3DRangeScan stored = gasp::toPointsScan(scan, "LIDAR");
  EXPECT_FALSE(stored.hasRangeImage);
  EXPECT_TRUE(stored.hasPoints3D);
  EXPECT_TRUE(gasp::isSweepObservation(stored));
  EXPECT_TRUE(gasp::isPointsObservation(stored));
  EXPECT_EQ(gasp::observationKind(stored), "a LiDAR sweep as 3D points (CObservation3DRangeScan without a range image)");
  mrpt::obs::CObservation3DRangeScan camera;  // a depth camera's scan is not one
  camera.hasRangeImage = true;
  EXPECT_FALSE(gasp::isSweepObservation(camera));
  EXPECT_FALSE(gasp::isPointsObservation(camera));
  EXPECT_EQ(gasp::observationKind(camera), "a depth image (CObservation3DRangeScan)");

  const std::string path = gasp::test::scratchDir() + "/points.bin";
  {
    mrpt::io::CFileGZOutputStream out(path);
    mrpt::serialization::archiveFrom(out) << stored;
  }
  mrpt::io::CFileGZInputStream in(path);
  mrpt::serialization::CSerializable::Ptr obj;
  mrpt::serialization::archiveFrom(in) >> obj;
  const auto read = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(obj);
  ASSERT_TRUE(read);
  const gasp::RgbdFrame frame = gasp::sweepFrameFromObservation(*read, "stored");
  const gasp::RangeScan cloud = gasp::rangeScanFrom(gasp::toPointCloud(scan, "LIDAR"));
  ASSERT_TRUE(frame.isSweep());
  EXPECT_EQ(frame.sensor_label, "LIDAR");
  EXPECT_NEAR(frame.timestamp, 1234.5, 1e-6);
  EXPECT_TRUE(frame.T_robot_camera.isApprox(scan.T_robot_sensor, 1e-6));
  EXPECT_EQ(frame.sweep->returnCount(), cloud.returnCount());
  EXPECT_EQ(frame.sweep->range_m.rows, cloud.range_m.rows);
  EXPECT_EQ(frame.sweep->range_m.cols, cloud.range_m.cols);
  EXPECT_EQ(cv::norm(frame.sweep->range_m, cloud.range_m, cv::NORM_INF), 0.0);
}

TEST(PointCloudSweep, ASimulatedSweepAsPointsGetsItsRingsColumnsAndEveryReturn) {
  for (const int lasers : {16, 64}) {
    const gasp::sim::LidarSensor sensor = gasp::sim::lidarSensor(lasers);
    gasp::Isometry3 T = gasp::Isometry3::Identity();
    T.translation() = Eigen::Vector3d(0.5, 0.0, 1.0);
    const gasp::RangeScan scan = gasp::sim::simulateLidarScan(gasp::sim::makeScene("room"), sensor, T, 3, 0);
    const std::vector<Eigen::Vector3d> points = scan.points();
    gasp::RangeScan back = gasp::rangeScanFrom(gasp::toPointCloud(scan, "CLOUD"));
    EXPECT_EQ(back.model, gasp::kPointCloudModel);
    ASSERT_EQ(back.range_m.rows, scan.range_m.rows) << lasers;
    for (std::size_t r = 0; r < scan.elevation_rad.size(); ++r)
      EXPECT_NEAR(back.elevation_rad[r], scan.elevation_rad[r], 1e-5) << lasers << ": row " << r;
    EXPECT_EQ(back.range_m.cols, scan.range_m.cols) << lasers;
    EXPECT_TRUE(gasp::coversWholeTurn(back));
    // Every return kept at its place (float points: within 1e-5 m), in the cell of its own
    // direction: within half a column of the column's azimuth and half a pitch of the row's
    // elevation (each point keeps its ray, so its place alone would not show a wrong cell).
    EXPECT_EQ(back.returnCount(), scan.returnCount()) << lasers;
    const std::vector<Eigen::Vector3d> after = back.points();
    EXPECT_LT(worstNearest(after, points, 400), 1e-4) << lasers;
    const double half_column = 0.5 * std::abs(gasp::azimuthStep(back)) + 1e-6, half_row = 0.5 * gasp::rowPitch(back) + 1e-6;
    int misplaced = 0;
    for (int r = 0; r < back.range_m.rows; ++r)
      for (int c = 0; c < back.range_m.cols; ++c) {
        if (!(back.range_m.at<float>(r, c) > 0.0f)) continue;
        const Eigen::Vector3d d = back.direction(r, c);
        const double el = std::atan2(d.z(), std::hypot(d.x(), d.y())), az = std::atan2(d.y(), d.x());
        if (std::abs(el - back.elevation_rad[static_cast<std::size_t>(r)]) > half_row ||
            std::abs(std::remainder(az - back.azimuth_rad[static_cast<std::size_t>(c)], 2 * M_PI)) > half_column)
          ++misplaced;
      }
    EXPECT_EQ(misplaced, 0) << lasers;
  }
}

// A ring that sees mostly sky keeps its few returns as a row, and a handful of stray points at
// elevations of no ring (multipath, a laser's offset seen close up) make no row of their own.
TEST(PointCloudSweep, ASparseRingIsARowAndStrayPointsAreNot) {
  const gasp::sim::LidarSensor sensor = gasp::sim::lidarSensor(16);
  gasp::Isometry3 T = gasp::Isometry3::Identity();
  T.translation() = Eigen::Vector3d(0.5, 0.0, 1.0);
  gasp::RangeScan scan = gasp::sim::simulateLidarScan(gasp::sim::makeScene("room"), sensor, T, 3, 0);
  const int top = scan.range_m.rows - 1;
  for (int c = 0; c < scan.range_m.cols; ++c)
    if (c % 33 != 0) scan.range_m.at<float>(top, c) = 0.0f;  // 3 % of the top ring left
  std::vector<Eigen::Vector3d> points = scan.points();
  for (int i = 0; i < 5; ++i) {  // four between rows 3 and 4, one above the top
    const double el = (i < 4 ? 0.5 * (scan.elevation_rad[3] + scan.elevation_rad[4]) : scan.elevation_rad[15] + 0.03);  // beyond half a pitch: left out
    points.push_back(4.0 * Eigen::Vector3d(std::cos(el) * std::cos(i), std::cos(el) * std::sin(i), std::sin(el)));
  }
  const gasp::RangeScan back = gasp::rangeScanFromPoints(points, "CLOUD");
  ASSERT_EQ(back.range_m.rows, 16);
  for (std::size_t r = 0; r < 16; ++r) EXPECT_NEAR(back.elevation_rad[r], scan.elevation_rad[r], 1e-5) << r;
  EXPECT_EQ(cv::countNonZero(back.range_m.row(top)), cv::countNonZero(scan.range_m.row(top)));
}

TEST(PointCloudSweep, TwoSimulatedSweepsAsPointCloudsRegister) {
  const gasp::sim::Scene room = gasp::sim::makeScene("room");
  const gasp::sim::LidarSensor sensor = gasp::sim::lidarSensor(16);
  gasp::Isometry3 T_a = gasp::Isometry3::Identity(), T_b = motion(1.0, 0.3, 35.0);
  T_a.translation() = Eigen::Vector3d(0.3, -0.2, 1.0);
  T_b.translation().z() = 1.05;
  const gasp::RangeScan a = gasp::rangeScanFrom(gasp::toPointCloud(gasp::sim::simulateLidarScan(room, sensor, T_a, 1, 0), "A"));
  const gasp::RangeScan b = gasp::rangeScanFrom(gasp::toPointCloud(gasp::sim::simulateLidarScan(room, sensor, T_b, 1, 1), "B"));
  const gasp::RangePairResult r = gasp::registerRangeScans(a, b);
  ASSERT_TRUE(r.pair.pose.success) << r.pair.pose.reason;
  const gasp::Isometry3 E = (T_b.inverse() * T_a).inverse() * r.pair.pose.T_target_source;
  EXPECT_LT(E.translation().norm(), 0.05);
  EXPECT_LT(Eigen::AngleAxisd(E.linear()).angle() * 180.0 / M_PI, 0.5);
}

// MRPT's real VLP-16 sample, its calibrated points given as a point cloud: the layout the points
// show is the sensor's, and the cloud registers to the packets' own sweep moved by known motions
// within the real scans' tolerance (2 cm / 0.2 deg), a half turn included.
TEST(PointCloudSweep, MrptsRealVlp16AsAPointCloudRegistersToItsPacketsSweepUnderKnownMotions) {
  if (!std::filesystem::exists(kVelodyne)) GTEST_SKIP() << kVelodyne << " not found (package mrpt-common)";
  mrpt::io::CFileGZInputStream in(kVelodyne);
  auto archive = mrpt::serialization::archiveFrom(in);
  const auto velodyne = std::dynamic_pointer_cast<mrpt::obs::CObservationVelodyneScan>(archive.ReadObject());
  ASSERT_TRUE(velodyne);
  const gasp::RangeScan packets = gasp::rangeScanFrom(*velodyne);
  const mrpt::obs::CObservationPointCloud cloud = gasp::toPointCloud(packets, "VLP16_CLOUD");
  const gasp::RangeScan scan = gasp::rangeScanFrom(cloud);
  ASSERT_EQ(scan.range_m.rows, 16);
  const std::vector<double> vlp16 = gasp::laserElevationsDeg("VLP-16", 16);
  std::vector<double> sorted = vlp16;
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t r = 0; r < 16; ++r) EXPECT_NEAR(scan.elevation_rad[r] * 180.0 / M_PI, sorted[r], 0.01) << r;
  // The sample's lasers return every other column of the packets' layout (docs/lidar.md): the
  // points' own step is two of its columns.
  EXPECT_NEAR(std::abs(gasp::azimuthStep(scan)), 2.0 * std::abs(gasp::azimuthStep(packets)), 0.02 * M_PI / 180.0);
  // A few share a cell: the sample's firings drift against a uniform step.
  EXPECT_GT(scan.returnCount(), packets.returnCount() * 98 / 100);
  EXPECT_NEAR(scan.timestamp, packets.timestamp, 1e-6);
  EXPECT_TRUE(scan.T_robot_sensor.isApprox(packets.T_robot_sensor, 1e-9));
  for (const gasp::Isometry3& T : {motion(0.5, 0.1, 10.0), motion(0.3, 1.0, 180.0), motion(0.0, 0.0, -90.0)}) {
    const gasp::RangePairResult r = gasp::registerRangeScans(scan, gasp::movedScan(packets, T));
    ASSERT_TRUE(r.pair.pose.success) << r.pair.pose.reason;
    const gasp::Isometry3 E = T.inverse() * r.pair.pose.T_target_source;
    EXPECT_LT(E.translation().norm(), 0.02);
    EXPECT_LT(Eigen::AngleAxisd(E.linear()).angle() * 180.0 / M_PI, 0.2);
  }
}

TEST(PointCloudSweep, ACloudThatIsNotOneSweepIsAnErrorNamingIt) {
  auto expectError = [](const mrpt::obs::CObservationPointCloud& cloud, const std::string& part) {
    try {
      gasp::rangeScanFrom(cloud);
      ADD_FAILURE() << "no error (" << part << ")";
    } catch (const gasp::Error& e) {
      EXPECT_NE(std::string(e.what()).find("point cloud 'BAD'"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-5.0, 5.0);
  std::vector<Eigen::Vector3d> cube;  // a stereo camera's cloud, say: no rings
  for (int i = 0; i < 20000; ++i) cube.emplace_back(u(rng), u(rng), u(rng));
  expectError(cloudOf(cube, "BAD"), "not a rotating LiDAR's rings");  // its elevations spread
  std::vector<Eigen::Vector3d> wide;  // two bands of elevation, each wider than half their spacing
  for (int i = 0; i < 20000; ++i) {
    const double el = (i % 2 ? 5.0 : -5.0) + 7.0 * (i % 1000) / 1000.0 - 3.5, az = 0.01 * i;
    wide.emplace_back(std::cos(el * M_PI / 180) * std::cos(az), std::cos(el * M_PI / 180) * std::sin(az), std::sin(el * M_PI / 180));
  }
  expectError(cloudOf(wide, "BAD"), "not a rotating LiDAR's rings");
  std::vector<Eigen::Vector3d> ring;  // a 2D scan's single ring
  for (int i = 0; i < 720; ++i) ring.emplace_back(3.0 * std::cos(i * M_PI / 360), 3.0 * std::sin(i * M_PI / 360), 0.0);
  expectError(cloudOf(ring, "BAD"), "1 rings");
  expectError(cloudOf({}, "BAD"), "0 points");
  mrpt::obs::CObservationPointCloud empty;
  empty.sensorLabel = "BAD";
  expectError(empty, "no points map");
  EXPECT_TRUE(gasp::isSweepObservation(empty));
}

// A rawlog of point clouds reads as a sequence of sweeps (gasp-odometry / gasp-slam --rawlog).
TEST(PointCloudSweep, ARawlogOfPointCloudsReadsAsSweeps) {
  const std::string dir = gasp::test::scratchDir();
  const gasp::sim::Scene room = gasp::sim::makeScene("room");
  const gasp::sim::LidarSensor sensor = gasp::sim::lidarSensor(16);
  {
    mrpt::io::CFileGZOutputStream out(dir + "/clouds.rawlog");
    auto archive = mrpt::serialization::archiveFrom(out);
    for (int i = 0; i < 3; ++i) {
      gasp::Isometry3 T = motion(0.1 * i, 0.0, 5.0 * i);
      T.translation().z() = 1.0;
      gasp::RangeScan sweep = gasp::sim::simulateLidarScan(room, sensor, T, 1, i);
      sweep.timestamp = 100.0 + 0.1 * i;
      archive << gasp::toPointCloud(sweep, "CLOUD");
    }
  }
  const std::vector<gasp::RgbdFrame> frames = sweepsOf(dir + "/clouds.rawlog");
  for (std::size_t n = 0; n < frames.size(); ++n) {
    const gasp::RgbdFrame& f = frames[n];
    ASSERT_TRUE(f.isSweep());
    EXPECT_EQ(f.sensor_label, "CLOUD");
    EXPECT_EQ(f.sweep->range_m.rows, 16);
    EXPECT_NEAR(f.timestamp, 100.0 + 0.1 * static_cast<double>(n), 1e-6);
  }
  EXPECT_EQ(frames.size(), 3u);
}

// gasp-simulate --point-clouds: the sweeps as CObservationPointCloud, which read back as the
// simulator's sweeps (their rings, columns and returns); the flag is a LiDAR's only.
TEST(PointCloudSweep, GaspSimulateWritesSweepsAsPointClouds) {
  const std::string dir = gasp::test::scratchDir() + "/clouds";
  const auto run = gasp::test::runProgram("gasp-simulate", "--sensor lidar16 --point-clouds --frames 8 --rate 10 --out " + dir);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(gasp::test::contains(run.output, "sweeps:      8 of VLP-16 as point clouds")) << run.output;
  const std::vector<gasp::RgbdFrame> frames = sweepsOf(dir + "/lidar.rawlog");
  for (const gasp::RgbdFrame& f : frames) {
    ASSERT_TRUE(f.isSweep());
    EXPECT_EQ(f.sweep->model, gasp::kPointCloudModel);
    EXPECT_EQ(f.sweep->range_m.rows, 16);
    EXPECT_EQ(f.sweep->range_m.cols, 1800);
  }
  EXPECT_EQ(frames.size(), 8u);
  const auto bad = gasp::test::runProgram("gasp-simulate", "--point-clouds --out " + dir + "/x");
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_TRUE(gasp::test::contains(bad.output, "--point-clouds is a LiDAR's output")) << bad.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/x"));
}

// gasp-simulate --sweep-motion: each column fired from the path's pose at its time. Column 0 is
// fired at the sweep's start, from the pose the ground truth gives, so it is the same as the still
// sweep's; the rest of the sweeps are skewed by the motion (deskewSweep's exactness:
// SimLidar.AMovingSweepDeskewedWithItsTwistLiesOnTheSceneSeenFromItsStart). The flag is a LiDAR's
// only.
TEST(PointCloudSweep, GaspSimulateSweepMotionFiresEachColumnFromItsOwnPose) {
  const std::string dir = gasp::test::scratchDir();
  const std::string still = dir + "/still", moving = dir + "/moving";
  // The room's path as the benchmarks take it (up to 0.3 m and 18 deg a sweep).
  const std::string args = " --sensor lidar16 --no-noise --frames 60 --rate 10 --out ";
  ASSERT_EQ(gasp::test::runProgram("gasp-simulate", args + still).exit_code, 0);
  const auto run = gasp::test::runProgram("gasp-simulate", "--sweep-motion" + args + moving);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(gasp::test::contains(run.output, "moving during each sweep")) << run.output;
  const std::vector<gasp::RgbdFrame> a = sweepsOf(still + "/lidar.rawlog"), b = sweepsOf(moving + "/lidar.rawlog");
  ASSERT_EQ(a.size(), 60u);
  ASSERT_EQ(b.size(), 60u);
  int skewed = 0;
  for (std::size_t k = 0; k < b.size(); ++k) {
    const cv::Mat &x = a[k].sweep->range_m, &y = b[k].sweep->range_m;
    int both = 0, close = 0;
    for (int r = 0; r < x.rows; ++r) {
      EXPECT_NEAR(x.at<float>(r, 0), y.at<float>(r, 0), 1e-5f) << k << ", row " << r;  // the same pose, rounded
      for (int c = 1; c < x.cols; ++c) {
        const float p = x.at<float>(r, c), q = y.at<float>(r, c);
        if (p > 0.0f && q > 0.0f) ++both, close += std::abs(p - q) <= 0.02f ? 1 : 0;
      }
    }
    skewed += close < 0.9 * both ? 1 : 0;
  }
  EXPECT_GE(skewed, 50);  // the path stands still for a few sweeps
  const auto bad = gasp::test::runProgram("gasp-simulate", "--sweep-motion --out " + dir + "/x");
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_TRUE(gasp::test::contains(bad.output, "--sweep-motion is a LiDAR's")) << bad.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/x"));
}
