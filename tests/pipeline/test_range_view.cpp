// A LiDAR sweep as a depth view (gasp/pipeline/range_view.h): the binning, its refusals, and
// simulated sweeps registered without a prior, 16 to 64 lasers, up to half turns.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "gasp/core/error.h"
#include "gasp/pipeline/range_view.h"
#include "gasp/sim/lidar.h"
#include "gasp/sim/scene.h"
#include "gasp/superpixels/depth_superpixels.h"

namespace {

using gasp::Isometry3;
using gasp::RangeScan;

constexpr double kDeg = M_PI / 180.0;

/// Two lasers 1 deg apart (10 columns a bin), `columns` columns 0.1 deg apart counter-clockwise
/// from azimuth 0, no returns.
RangeScan oneRow(int columns) {
  RangeScan s;
  std::vector<double> az;
  for (int c = 0; c < columns; ++c) az.push_back(0.1 * kDeg * c);
  s.setLayout({-1.0, 0.0}, az);  // two rows 1 deg apart: 10 columns per cell
  return s;
}

double angleDeg(const Isometry3& T) { return Eigen::AngleAxisd(T.linear()).angle() / kDeg; }

}  // namespace

TEST(RangeView, TheColumnsAreBinnedToTheRowsPitch) {
  const gasp::sim::Scene room = gasp::sim::makeScene("room");
  Isometry3 T = Isometry3::Identity();
  T.translation() = Eigen::Vector3d(0.6, 0.0, 1.0);
  // VLP-16 rows 2 deg apart: 10 columns of 0.2 deg; HDL-32E 1.33 deg: 7 (a whole turn keeps
  // whole bins, 257); 64 lasers 0.43 deg: 2.
  for (const auto& [lasers, bin, cells] : {std::tuple{16, 10, 180}, std::tuple{32, 7, 257}, std::tuple{64, 2, 900}}) {
    const RangeScan s = gasp::sim::simulateLidarScan(room, gasp::sim::lidarSensor(lasers), T);
    EXPECT_EQ(gasp::rangeBinColumns(s), bin) << lasers;
    const auto [range, projection] = gasp::binRangeScan(s, gasp::lidarSuperpixelParams());
    EXPECT_EQ(range.rows, lasers);
    EXPECT_EQ(range.cols, cells);
    EXPECT_EQ(projection.width(), cells);
    EXPECT_FALSE(projection.isPinhole());
  }
}

TEST(RangeView, ASweepPastAWholeTurnKeepsOneTurnOfBins) {
  // 1810 columns of 0.2 deg (a sweep whose packets overlap by 2 deg): 180 bins of 2 deg.
  RangeScan s;
  std::vector<double> az;
  for (int c = 0; c < 1810; ++c) az.push_back(-0.2 * kDeg * c);
  s.setLayout(gasp::laserElevationsDeg("VLP-16", 16), az);
  s.range_m.setTo(10.0f);
  const auto [range, projection] = gasp::binRangeScan(s, gasp::lidarSuperpixelParams());
  EXPECT_EQ(range.cols, 180);
  EXPECT_EQ(projection.width(), 180);
}

TEST(RangeView, ACellIsTheMeanPointOfItsBinsNearestSurface) {
  RangeScan s = oneRow(20);
  // Row 1, first bin: six returns on a surface near 5 m, two on a wall at 9 m behind, two lost.
  const float r[10] = {5.00f, 5.02f, 9.0f, 4.98f, 0.0f, 5.01f, 9.1f, 5.03f, 0.0f, 4.99f};
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int c = 0; c < 10; ++c) {
    s.range_m.at<float>(1, c) = r[c];
    if (r[c] > 0.0f && r[c] < 6.0f) sum += static_cast<double>(r[c]) * s.direction(1, c);
  }
  const Eigen::Vector3d mean = sum / 6.0;
  const auto [range, projection] = gasp::binRangeScan(s, gasp::lidarSuperpixelParams());
  ASSERT_EQ(range.cols, 2);
  EXPECT_NEAR(range.at<float>(1, 0), mean.norm(), 1e-5);
  EXPECT_TRUE(projection.unproject(0, 1, range.at<float>(1, 0)).isApprox(mean, 1e-6));
  EXPECT_EQ(range.at<float>(0, 0), 0.0f);  // no return: no cell
  EXPECT_EQ(range.at<float>(1, 1), 0.0f);
  // The grid: the first bin's middle azimuth, a bin's width as the step.
  EXPECT_NEAR(projection.grid().azimuth_first_rad, 0.45 * kDeg, 1e-12);
  EXPECT_NEAR(projection.grid().azimuth_step_rad, 1.0 * kDeg, 1e-12);
}

TEST(RangeView, AScanThatIsNoRangeImageIsRefused) {
  RangeScan s = oneRow(20);
  s.azimuth_rad[7] += 0.05 * kDeg;  // uneven columns
  EXPECT_THROW(gasp::makeRangeView(s, gasp::lidarSuperpixelParams()), gasp::Error);
  s = oneRow(20);
  s.elevation_rad.pop_back();  // a row without its elevation
  EXPECT_THROW(gasp::makeRangeView(s, gasp::lidarSuperpixelParams()), gasp::Error);
  s = oneRow(20);
  s.elevation_rad = {0.0, -0.01};  // descending
  EXPECT_THROW(gasp::makeRangeView(s, gasp::lidarSuperpixelParams()), gasp::Error);
  s = oneRow(20);
  s.azimuth_rad[5] = std::nan("");  // not a number past the first two columns
  EXPECT_THROW(gasp::makeRangeView(s, gasp::lidarSuperpixelParams()), gasp::Error);
  s = oneRow(20);
  s.azimuth_rad[1] = s.azimuth_rad[0];  // no step
  EXPECT_THROW(gasp::makeRangeView(s, gasp::lidarSuperpixelParams()), gasp::Error);
  s = oneRow(20);
  s.ray = cv::Mat::zeros(2, 19, CV_32FC3);  // a ray table of another size
  EXPECT_THROW(gasp::makeRangeView(s, gasp::lidarSuperpixelParams()), gasp::Error);
  EXPECT_THROW(gasp::movedScan(s, Isometry3::Identity()), gasp::Error);
  EXPECT_THROW(gasp::refineOnReturns(oneRow(20), s, Isometry3::Identity()), gasp::Error);
  s = oneRow(20);
  s.range_m.convertTo(s.range_m, CV_64F);  // ranges of another type
  EXPECT_THROW(gasp::makeRangeView(s, gasp::lidarSuperpixelParams()), gasp::Error);
  // A range image is segmented at full resolution only: its cells are binned already.
  gasp::SuperpixelParams coarse = gasp::lidarSuperpixelParams();
  coarse.processing_step_px = 2;
  EXPECT_THROW(gasp::makeRangeView(oneRow(20), coarse), gasp::Error);
}

TEST(RangeView, AnEmptySweepHasNoPatches) {
  const gasp::DepthView v = gasp::makeRangeView(oneRow(40), gasp::lidarSuperpixelParams());
  EXPECT_TRUE(v.segmentation.patches.empty());
  EXPECT_FALSE(gasp::registerViews(v, v, gasp::lidarPairParams()).pose.success);
}

struct LidarMotion {
  int lasers;
  double forward_m, yaw_deg;
};

class SimulatedLidarPair : public ::testing::TestWithParam<LidarMotion> {};

// Two sweeps of the furnished room, the second moved and turned about the vertical axis, are
// registered with no prior (registerRangeScans: the binned views, then the returns) within 5 cm /
// 0.5 deg (the bound; exact truth).
TEST_P(SimulatedLidarPair, RegistersWithoutAPrior) {
  const LidarMotion m = GetParam();
  const gasp::sim::Scene room = gasp::sim::makeScene("room");
  const gasp::sim::LidarSensor sensor = gasp::sim::lidarSensor(m.lasers);
  Isometry3 T_world_a = Isometry3::Identity();
  T_world_a.translation() = Eigen::Vector3d(0.6, 0.0, 1.0);
  Isometry3 T_world_b = T_world_a;
  T_world_b.translation() += Eigen::Vector3d(m.forward_m, 0.2 * m.forward_m, 0.0);
  T_world_b.linear() = Eigen::AngleAxisd(m.yaw_deg * kDeg, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const RangeScan a = gasp::sim::simulateLidarScan(room, sensor, T_world_a, 1, 0);
  const RangeScan b = gasp::sim::simulateLidarScan(room, sensor, T_world_b, 1, 1);
  const gasp::RangePairResult rr = gasp::registerRangeScans(a, b);
  const gasp::PairResult& r = rr.pair;
  ASSERT_TRUE(r.pose.success) << r.pose.reason;
  EXPECT_TRUE(rr.pair.returns_refined) << rr.pair.returns_reason;
  const Isometry3 error = (T_world_b.inverse() * T_world_a).inverse() * r.pose.T_target_source;
  EXPECT_LT(error.translation().norm(), 0.05);
  EXPECT_LT(angleDeg(error), 0.5);
}

TEST(RangeView, TheReturnsRefinementSaysWhyItFindsNoTerms) {
  const gasp::sim::Scene room = gasp::sim::makeScene("room");
  Isometry3 T = Isometry3::Identity();
  T.translation() = Eigen::Vector3d(0.6, 0.0, 1.0);
  const RangeScan s = gasp::sim::simulateLidarScan(room, gasp::sim::lidarSensor(16), T);
  // From 10 cm and 2 deg off it comes back to the truth; 5 m off, no return lies within any gate
  // of another.
  Isometry3 off = Isometry3::Identity();
  off.linear() = Eigen::AngleAxisd(2.0 * kDeg, Eigen::Vector3d(0.3, 0.2, 1.0).normalized()).toRotationMatrix();
  off.translation() = Eigen::Vector3d(0.06, -0.05, 0.06);
  const gasp::RegistrationResult near = gasp::refineOnReturns(s, s, off);
  ASSERT_TRUE(near.success) << near.reason;
  EXPECT_LT(near.T_target_source.translation().norm(), 5e-3);  // the returns are 2 cm noisy
  EXPECT_LT(angleDeg(near.T_target_source), 0.05);
  Isometry3 far = Isometry3::Identity();
  far.translation() = Eigen::Vector3d(0.0, 0.0, 5.0);
  const gasp::RegistrationResult none = gasp::refineOnReturns(s, s, far);
  EXPECT_FALSE(none.success);
  EXPECT_NE(none.reason.find("point-to-plane terms"), std::string::npos) << none.reason;
  gasp::ReturnsRefineParams bad;
  bad.gates_m[1] = 0.0;
  EXPECT_THROW(gasp::refineOnReturns(s, s, Isometry3::Identity(), bad), gasp::Error);
}

INSTANTIATE_TEST_SUITE_P(Sweeps, SimulatedLidarPair,
                         ::testing::Values(LidarMotion{16, 0.3, 20}, LidarMotion{16, 1.0, 90}, LidarMotion{16, 1.5, 180},
                                           LidarMotion{32, 0.8, -45}, LidarMotion{64, 0.3, 20},
                                           LidarMotion{64, 1.5, 180}),
                         [](const auto& motion) {
                           return std::to_string(motion.param.lasers) + "Lasers" +
                                  std::to_string(static_cast<int>(std::lround(std::abs(motion.param.yaw_deg)))) + "Deg";
                         });

// A LiDAR's pair values are a camera's (a params file's pair sections) made a LiDAR's: lengths
// that compare centroids scaled, those that compare points and the sampling set, the symmetry
// test and the likelihood's violation charge from the lidar section, the other counts, limits and
// switches kept (docs/lidar.md "Parameters").
TEST(RangeView, TheLidarsPairValuesAreTheCamerasMadeALidars) {
  gasp::PairParams camera;
  camera.hypothesise.pose.ransac.min_inliers = 11;
  camera.certify.symmetry_test = true;
  camera.certify.min_likelihood_ratio = 500.0;
  camera.associate.match.r_dev_m = 0.03;
  camera.refine.pixels.pixel_step = 4;
  gasp::LidarParams lidar;
  lidar.symmetry_test = false;
  lidar.violation_nats = 1.5;
  const gasp::PairParams p = gasp::lidarPairParams(lidar, camera);
  EXPECT_EQ(p.hypothesise.pose.ransac.min_inliers, 11);
  EXPECT_DOUBLE_EQ(p.certify.min_likelihood_ratio, 500.0);
  EXPECT_FALSE(p.certify.symmetry_test);
  EXPECT_DOUBLE_EQ(p.certify.violation_nats, 1.5);
  EXPECT_DOUBLE_EQ(p.associate.match.r_dev_m, 0.03 * gasp::lidarCentroidScale(lidar));
  EXPECT_DOUBLE_EQ(p.hypothesise.pose.ransac.inlier.distance_m,
                   camera.hypothesise.pose.ransac.inlier.distance_m * gasp::lidarCentroidScale(lidar));
  EXPECT_EQ(p.refine.pixels.pixel_step, 1);
  EXPECT_DOUBLE_EQ(p.refine.pixels.sample_spacing_deg, lidar.dense_sample_spacing_deg);
  EXPECT_EQ(gasp::PairParams{}.refine.pixels.sample_spacing_deg, 0.0);  // a camera's: pixel_step alone
  EXPECT_DOUBLE_EQ(p.certify.visibility.gate_m, 5.0 * lidar.range_sigma_m);
  EXPECT_DOUBLE_EQ(p.segment.target_patch_area_m2, lidar.patch_area_m2);
  const gasp::PairParams defaults = gasp::lidarPairParams(gasp::LidarParams{});
  EXPECT_EQ(defaults.hypothesise.pose.ransac.min_inliers, gasp::PairParams{}.hypothesise.pose.ransac.min_inliers);
  EXPECT_TRUE(defaults.certify.symmetry_test);
  EXPECT_DOUBLE_EQ(defaults.certify.violation_nats, std::log(10.0));
  EXPECT_FALSE(gasp::PairParams{}.certify.symmetry_test);  // a camera's: neither
  EXPECT_EQ(gasp::PairParams{}.certify.violation_nats, 0.0);
  lidar.violation_nats = -1.0;
  EXPECT_THROW(gasp::validate(lidar), gasp::Error);
  lidar.violation_nats = 1.5;
  lidar.dense_sample_spacing_deg = -0.1;
  EXPECT_THROW(gasp::validate(lidar), gasp::Error);
  lidar.dense_sample_spacing_deg = 0.873;
  EXPECT_TRUE(defaults.ground_search.enabled);
  lidar.ground_search = false;
  lidar.ground_search_max_offset_m = 12.5;
  const gasp::PairParams unsearched = gasp::lidarPairParams(lidar, camera);
  EXPECT_FALSE(unsearched.ground_search.enabled);
  EXPECT_DOUBLE_EQ(unsearched.ground_search.max_offset_m, 12.5);
  lidar.ground_search_max_offset_m = 0.0;
  EXPECT_THROW(gasp::validate(lidar), gasp::Error);
  lidar.ground_search_max_offset_m = 81.0;  // beyond twice the search's range
  EXPECT_THROW(gasp::validate(lidar), gasp::Error);
}
