// The written folder reads back as a TUM dataset; same options give byte-identical files; bad
// input gives gasp::Error.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>

#include "gasp/core/error.h"
#include "gasp/core/tum_dataset.h"
#include "gasp/sim/writer.h"
#include "gasp_test_data.h"

namespace fs = std::filesystem;

namespace {

std::string readAll(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// Relative path -> contents of every file under dir.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files[fs::relative(e.path(), dir).string()] = readAll(e.path());
  return files;
}

gasp::sim::SimulationOptions smallOptions() {
  gasp::sim::SimulationOptions o;
  o.scene = "sparse";
  o.frames = 8;
  o.seed = 3;
  return o;
}

}  // namespace

TEST(SimWriter, FolderReadsBackAsTumDataset) {
  const std::string dir = gasp::test::scratchDir() + "/seq";
  const auto summary = gasp::sim::writeSimulation(smallOptions(), dir);
  EXPECT_EQ(summary.frames, 8);
  EXPECT_EQ(summary.scene, "sparse");
  EXPECT_GT(summary.valid_pixel_share, 0.8);
  EXPECT_LE(summary.valid_pixel_share, 1.0);
  ASSERT_EQ(summary.segments.size(), 4u);

  const auto ds = gasp::TumDataset::open(dir);
  ASSERT_EQ(ds.size(), 8u);
  EXPECT_EQ(ds.countWithGroundTruth(), 8u);
  EXPECT_NE(ds.intrinsicsSource().find("intrinsics.txt"), std::string::npos);
  EXPECT_EQ(ds.intrinsics(), gasp::CameraIntrinsics::rosDefault());

  const gasp::sim::Simulation sim(smallOptions());
  for (std::size_t i = 0; i < ds.size(); ++i) {
    const auto f = sim.frame(static_cast<int>(i));
    EXPECT_NEAR(ds.frame(i).timestamp, f.timestamp, 1e-6);
    ASSERT_TRUE(ds.frame(i).T_world_camera.has_value());
    EXPECT_TRUE(ds.frame(i).T_world_camera->isApprox(f.T_world_camera, 1e-6));
    const cv::Mat depth = ds.loadDepth(i);
    EXPECT_LE(cv::norm(depth, f.depth, cv::NORM_INF), 1e-6) << "file = in-memory frame";
    const std::string label_path = dir + "/labels/" + gasp::sim::formatTimestamp(f.timestamp) + ".png";
    const cv::Mat labels = gasp::loadDepthRaw(label_path);
    EXPECT_EQ(cv::norm(labels, f.labels, cv::NORM_INF), 0.0);
  }
  for (const char* name : {"segments.txt", "surfaces.txt", "scene.txt", "groundtruth.txt"})
    EXPECT_TRUE(fs::exists(fs::path(dir) / name)) << name;
  EXPECT_NE(readAll(fs::path(dir) / "segments.txt").find("roll_180"), std::string::npos);
  EXPECT_NE(readAll(fs::path(dir) / "scene.txt").find("seed: 3"), std::string::npos);
}

TEST(SimWriter, SameOptionsGiveByteIdenticalFiles) {
  const std::string root = gasp::test::scratchDir();
  gasp::sim::writeSimulation(smallOptions(), root + "/a");
  gasp::sim::writeSimulation(smallOptions(), root + "/b");
  auto other = smallOptions();
  other.seed = 4;
  gasp::sim::writeSimulation(other, root + "/c");
  const auto a = snapshot(root + "/a");
  const auto b = snapshot(root + "/b");
  const auto c = snapshot(root + "/c");
  EXPECT_EQ(a.size(), 8u * 2u + 6u);  // depth + labels PNGs, 6 text files
  EXPECT_TRUE(a == b);
  const std::string first_depth = "depth/" + gasp::sim::formatTimestamp(1000.0) + ".png";
  ASSERT_EQ(a.count(first_depth), 1u);
  EXPECT_NE(a.at(first_depth), c.at(first_depth));
  EXPECT_EQ(a.at("groundtruth.txt"), c.at("groundtruth.txt"));
}

TEST(SimWriter, BadInputIsAnError) {
  const std::string root = gasp::test::scratchDir();
  try {
    gasp::sim::makeScene("castle");
    FAIL() << "expected gasp::Error";
  } catch (const gasp::Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("castle"), std::string::npos);
    for (const auto& name : gasp::sim::sceneNames()) EXPECT_NE(msg.find(name), std::string::npos) << msg;
  }
  auto o = smallOptions();
  o.scene = "castle";
  EXPECT_THROW(gasp::sim::writeSimulation(o, root + "/x"), gasp::Error);
  EXPECT_FALSE(fs::exists(root + "/x")) << "nothing is written for bad options";
  o = smallOptions();
  o.frames = 0;
  EXPECT_THROW(gasp::sim::writeSimulation(o, root + "/x"), gasp::Error);
  // A regular file where a folder is needed.
  std::ofstream(root + "/file") << "x";
  EXPECT_THROW(gasp::sim::writeSimulation(smallOptions(), root + "/file"), gasp::Error);
  EXPECT_THROW(gasp::sim::writeSimulation(smallOptions(), root + "/file/sub"), gasp::Error);
}

TEST(SimWriter, EveryNamedSceneBuilds) {
  for (const auto& name : gasp::sim::sceneNames()) {
    const auto scene = gasp::sim::makeScene(name);
    EXPECT_EQ(scene.name, name);
    EXPECT_FALSE(scene.objects.empty());
    EXPECT_FALSE(scene.description.empty());
  }
  EXPECT_EQ(gasp::sim::makeScene("plane").objects.size(), 1u);
  EXPECT_EQ(gasp::sim::makeScene("corridor").objects.size(), 2u);
  EXPECT_LE(gasp::sim::makeScene("sparse").objects.size(), 4u);
}

TEST(SimWriter, ARealTumFolderIsNeverOverwritten) {
  // A folder whose depth.txt the simulator did not write is real data: refused, untouched.
  const std::string root = gasp::test::scratchDir() + "/real";
  fs::create_directories(root);
  const std::string listing = "# depth maps\n# timestamp filename\n1305031102.160407 depth/1305031102.160407.png\n";
  std::ofstream(root + "/depth.txt") << listing;
  try {
    gasp::sim::writeSimulation(smallOptions(), root);
    FAIL() << "expected gasp::Error";
  } catch (const gasp::Error& e) {
    EXPECT_NE(std::string(e.what()).find("did not write"), std::string::npos) << e.what();
  }
  std::ifstream in(root + "/depth.txt");
  const std::string after((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(after, listing);
  EXPECT_FALSE(fs::exists(root + "/groundtruth.txt"));
  // An earlier simulation in the same folder is replaced.
  const std::string sim = gasp::test::scratchDir() + "/sim";
  EXPECT_NO_THROW(gasp::sim::writeSimulation(smallOptions(), sim));
  EXPECT_NO_THROW(gasp::sim::writeSimulation(smallOptions(), sim));
}
