// MRPT's own maps from GASP's output: observations2map, with GASP's plugin preloaded, over a
// gasp-slam simple map written with --simplemap-points builds MRPT's points map beside GASP's
// superpixel map, and the points lie where gasp-slam --cloud puts them; MRPT's voxel map
// (COccupancyGridMap3D) takes the same simple map.
#include <gtest/gtest.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/maps/COccupancyGridMap3D.h>
#include <mrpt/maps/CSimpleMap.h>
#include <mrpt/serialization/CArchive.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <set>
#include <tuple>
#include <vector>

#include "gasp_test_data.h"
#include "program_run.h"

namespace {

using Voxel = std::tuple<std::int64_t, std::int64_t, std::int64_t>;

Voxel voxelOf(double x, double y, double z, double size) {
  return {static_cast<std::int64_t>(std::floor(x / size)), static_cast<std::int64_t>(std::floor(y / size)),
          static_cast<std::int64_t>(std::floor(z / size))};
}

/// The points of a text file of "x y z" lines, or of an ASCII PLY's vertices (after end_header).
std::vector<Voxel> voxelsOfPoints(const std::string& path, double size, bool ply) {
  std::ifstream in(path);
  std::string line;
  if (ply)
    while (std::getline(in, line) && line != "end_header") {
    }
  std::vector<Voxel> voxels;
  double x = 0, y = 0, z = 0;
  while (std::getline(in, line))
    if (std::istringstream(line) >> x >> y >> z) voxels.push_back(voxelOf(x, y, z, size));
  return voxels;
}

constexpr const char* kTool = "/usr/bin/observations2map";

/// observations2map with GASP's plugin preloaded: the maps of `ini_keys` ([MappingApplication]
/// lines) built from `simplemap`, written to PREFIX_<class>_<index>...
gasp::test::ProgramRun observations2map(const std::string& ini_keys, const std::string& simplemap,
                                        const std::string& prefix) {
  std::ofstream(prefix + ".ini") << "[MappingApplication]\n" << ini_keys;
  return gasp::test::runCommand("LD_PRELOAD=" + std::string(GASP_MRPT_PLUGIN) + " " + kTool + " " + prefix + ".ini " +
                                simplemap + " " + prefix + " < /dev/null 2>&1");
}

/// The share of the cloud's voxels (PLY) that hold points of the map (text "x y z" lines).
double cloudVoxelsCovered(const std::vector<Voxel>& map, const std::string& ply, double voxel) {
  const std::set<Voxel> occupied(map.begin(), map.end());
  const std::vector<Voxel> cloud = voxelsOfPoints(ply, voxel, true);
  if (cloud.empty()) return 0.0;
  std::size_t covered = 0;
  for (const Voxel& v : cloud) covered += occupied.count(v);
  return static_cast<double>(covered) / static_cast<double>(cloud.size());
}

/// The first line of a superpixel map's patches file: "# gasp::CSuperpixelMap: V views, N patches ...".
std::size_t patchesOf(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  const auto at = line.find("views, ");
  return at == std::string::npos ? 0 : std::stoul(line.substr(at + 7));
}

}  // namespace

TEST(Observations2Map, APointsMapBesideTheSuperpixelMapAgreesWithTheCloud) {
  if (!std::filesystem::exists(kTool)) GTEST_SKIP() << "skipped: no " << kTool << " (Debian: mrpt-apps)";
  const std::string out = gasp::test::scratchDir();
  const auto sim = gasp::test::runProgram("gasp-simulate", "--out " + out + "/room --frames 20 --rate 10");
  ASSERT_EQ(sim.exit_code, 0) << sim.output;
  const double voxel = 0.05;
  for (const bool points : {false, true}) {
    const std::string name = out + (points ? "/with" : "/without");
    const auto slam = gasp::test::runProgram(
        "gasp-slam", "--tum " + out + "/room --out " + name + ".txt --simplemap " + name + ".simplemap --cloud " + name +
                         ".ply --voxel 0.05" + (points ? " --simplemap-points" : ""));
    ASSERT_TRUE(slam.exit_code == 0 || slam.exit_code == 3) << slam.output;
    const auto run = observations2map("pointsMap_count=1\nsuperpixelMap_count=1\n", name + ".simplemap", name + "_map");
    ASSERT_EQ(run.exit_code, 0) << run.output;
    // GASP's map is built either way.
    EXPECT_GT(std::filesystem::file_size(name + "_map_gasp__CSuperpixelMap_01_patches.txt"), 0u) << run.output;
    const std::vector<Voxel> map = voxelsOfPoints(name + "_map_mrpt__maps__CSimplePointsMap_00.txt", voxel, false);
    if (!points) {  // the range images alone: MRPT's points map takes nothing from them
      EXPECT_TRUE(map.empty()) << map.size();
      continue;
    }
    ASSERT_GT(map.size(), 10000u);
    ASSERT_GT(voxelsOfPoints(name + ".ply", voxel, true).size(), 1000u);
    // Every voxel of gasp-slam's cloud (depth up to 4 m) holds points of MRPT's map: the same
    // frames at the same poses.
    EXPECT_GT(cloudVoxelsCovered(map, name + ".ply", voxel), 0.99);

    // MRPT 2.5's octomap-free voxel map, COccupancyGridMap3D, in the same run: observations2map
    // takes the three together and GASP's map is the same file. (The grid unprojects each scan at
    // its decimation, which cuts the points the scan stores, so the points map beside it gets
    // fewer: docs/mrpt.md.)
    const auto three = observations2map(
        "pointsMap_count=1\nsuperpixelMap_count=1\nmrpt::maps::COccupancyGridMap3D_count=1\n", name + ".simplemap",
        name + "_3map");
    ASSERT_EQ(three.exit_code, 0) << three.output;
    EXPECT_EQ(gasp::test::fileText(name + "_3map_gasp__CSuperpixelMap_02_patches.txt"),
              gasp::test::fileText(name + "_map_gasp__CSuperpixelMap_01_patches.txt"));
    EXPECT_GT(std::filesystem::file_size(name + "_3map_mrpt__maps__CSimplePointsMap_01.txt"), 0u);
    // The voxel map of the same simple map (observations2map writes no file of it): the cloud's
    // surfaces are its occupied voxels, but where rays of other keyframes graze them and the
    // grid's own free-space update clears them.
    mrpt::maps::CSimpleMap simple;
    {
      mrpt::io::CFileGZInputStream in(name + ".simplemap");
      mrpt::serialization::archiveFrom(in) >> simple;
    }
    mrpt::maps::COccupancyGridMap3D grid(mrpt::math::TPoint3D(-8, -8, -4), mrpt::math::TPoint3D(8, 8, 4), 0.25f);
    grid.loadFromSimpleMap(simple);
    std::ifstream ply(name + ".ply");
    std::string line;
    while (std::getline(ply, line) && line != "end_header") {
    }
    std::size_t points_in = 0, occupied_at = 0;
    double x = 0, y = 0, z = 0;
    while (std::getline(ply, line))
      if (std::istringstream(line) >> x >> y >> z) {
        ++points_in;
        occupied_at += grid.getFreenessByPos(x, y, z) < 0.5f;
      }
    ASSERT_GT(points_in, 1000u);
    EXPECT_GT(static_cast<double>(occupied_at), 0.7 * static_cast<double>(points_in))
        << occupied_at << " of " << points_in << " cloud points in occupied voxels";
  }
}

// A LiDAR's keyframes: MRPT 2.5's points maps insert no rotating scan, and place a point cloud at
// its sensorPose without the robot's pose; with --simplemap-points each sweep is a 3D range scan of
// its points, which they insert at the keyframe's pose and GASP's map reads as the same sweep.
TEST(Observations2Map, ALidarsPointsMapAgreesWithTheCloudAndGaspReadsTheSameSweeps) {
  if (!std::filesystem::exists(kTool)) GTEST_SKIP() << "skipped: no " << kTool << " (Debian: mrpt-apps)";
  const std::string out = gasp::test::scratchDir();
  const auto sim = gasp::test::runProgram("gasp-simulate", "--sensor lidar16 --frames 60 --rate 10 --out " + out + "/lidar");
  ASSERT_EQ(sim.exit_code, 0) << sim.output;
  const double voxel = 0.1;
  std::size_t patches[2] = {0, 0};
  for (const bool points : {false, true}) {
    const std::string name = out + (points ? "/with" : "/without");
    const auto slam = gasp::test::runProgram(
        "gasp-slam", "--rawlog " + out + "/lidar/lidar.rawlog --out " + name + ".txt --simplemap " + name +
                         ".simplemap --cloud " + name + ".ply --voxel 0.1" + (points ? " --simplemap-points" : ""));
    ASSERT_TRUE(slam.exit_code == 0 || slam.exit_code == 3) << slam.output;
    const auto run = observations2map("pointsMap_count=1\nsuperpixelMap_count=1\n", name + ".simplemap", name + "_map");
    ASSERT_EQ(run.exit_code, 0) << run.output;
    patches[points] = patchesOf(name + "_map_gasp__CSuperpixelMap_01_patches.txt");
    const std::vector<Voxel> map = voxelsOfPoints(name + "_map_mrpt__maps__CSimplePointsMap_00.txt", voxel, false);
    if (!points) {  // rotating scans: MRPT's points map takes nothing from them
      EXPECT_TRUE(map.empty()) << map.size();
      continue;
    }
    ASSERT_GT(map.size(), 100000u);
    ASSERT_GT(voxelsOfPoints(name + ".ply", voxel, true).size(), 5000u);
    // A voxel of the cloud holds the mean of its returns, which can fall where no single sparse
    // return of MRPT's map lies: 98 %, not all.
    EXPECT_GT(cloudVoxelsCovered(map, name + ".ply", voxel), 0.98);
  }
  // GASP's map from the sweeps' points: their layout found again, the same surfaces.
  ASSERT_GT(patches[0], 500u);
  EXPECT_NEAR(static_cast<double>(patches[1]), static_cast<double>(patches[0]), 0.02 * static_cast<double>(patches[0]));
}
