// gasp::CSuperpixelMap: insertion of real RGB-D and range-only scans (sensorPose and robot pose
// honoured), serialization, ini creation, visualisation, files, GASP-backed matching ratio and
// likelihood, and bad input.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/maps/CMultiMetricMap.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/opengl/COpenGLScene.h>
#include <mrpt/opengl/CPointCloudColoured.h>
#include <mrpt/opengl/CSetOfObjects.h>
#include <mrpt/opengl/CSetOfTriangles.h>
#include <mrpt/serialization/CArchive.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <thread>
#include <vector>

#include "gasp/core/undistortion.h"
#include "gasp/mrpt/CSuperpixelMap.h"
#include "gasp/mrpt/superpixel_map_view.h"
#include "gasp/rawlog/range_scan.h"
#include "gasp/sim/lidar.h"
#include "gasp/sim/scene.h"
#include "gasp/superpixels/depth_superpixels.h"
#include "gasp_test_data.h"
#include "mrpt_test_helpers.h"

using namespace gasp;
using gasp::test::someMount;
using gasp::test::tumObservation;

namespace {

Isometry3 someRobotPose() {
  Isometry3 P = Isometry3::Identity();
  P.linear() = Eigen::AngleAxisd(-0.7, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  P.translation() = Eigen::Vector3d(1.5, -2.0, 0.1);
  return P;
}

std::vector<std::uint8_t> serialize(const mrpt::serialization::CSerializable& o) {
  mrpt::io::CMemoryStream buf;
  mrpt::serialization::archiveFrom(buf) << o;
  const auto* p = static_cast<const std::uint8_t*>(buf.getRawBufferData());
  return {p, p + buf.getTotalBytesCount()};
}

mrpt::serialization::CSerializable::Ptr deserialize(const std::vector<std::uint8_t>& bytes) {
  mrpt::io::CMemoryStream buf;
  buf.assignMemoryNotOwn(bytes.data(), bytes.size());
  mrpt::serialization::CSerializable::Ptr o;
  mrpt::serialization::archiveFrom(buf) >> o;
  return o;
}

std::vector<MapPatch> directPatches(const TumDataset& ds, std::size_t i, const Isometry3& T_map_camera) {
  const RgbdFrame f = frameFromTum(ds, i, false);
  const auto seg = segmentDepthSuperpixels(f.depth_m, f.depth_intrinsics);
  SuperpixelMapView v;
  v.view.segmentation = seg;
  v.T_map_camera = T_map_camera;
  std::vector<MapPatch> out;
  appendMapPatches(v, 0, out);
  return out;
}

}  // namespace

TEST(SuperpixelMap, InsertsRgbdAndRangeOnlyScansInTheMapFrame) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  const auto ds = TumDataset::open(dir);
  const Isometry3 S = someMount(), P = someRobotPose();
  // The patches must be the camera-frame decomposition moved by robot pose * sensorPose.
  const auto expected = directPatches(ds, 0, P * S);
  ASSERT_GT(expected.size(), 100u);
  for (const bool rgb : {true, false}) {
    CSuperpixelMap map;
    EXPECT_TRUE(map.isEmpty());
    const auto obs = tumObservation(ds, 0, rgb, S);
    ASSERT_TRUE(map.insertObservation(*obs, toCPose3D(P)));
    ASSERT_EQ(map.views().size(), 1u);
    const auto patches = map.patchesInMapFrame();
    ASSERT_EQ(patches.size(), expected.size()) << (rgb ? "rgb-d" : "range-only");
    for (std::size_t k = 0; k < patches.size(); ++k) {
      EXPECT_LT((patches[k].centroid - expected[k].centroid).norm(), 1e-4);
      EXPECT_LT((patches[k].normal - expected[k].normal).norm(), 1e-6);
    }
    EXPECT_EQ(map.views()[0].patch_rgb.empty(), !rgb);
    EXPECT_NE(map.asString().find(std::to_string(patches.size()) + " surface patches"), std::string::npos);
  }
}

TEST(SuperpixelMap, TestsRgbdRawlogFromMrptInserts) {
  const std::string path = "/usr/share/mrpt/datasets/tests_rgbd.rawlog";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not installed (Debian package mrpt-common); skipping";
  const auto scans = gasp::test::readScans(path);
  ASSERT_FALSE(scans.empty());
  const auto& scan = *scans.front();
  // The premise: the range camera and the intensity camera have different intrinsics here.
  EXPECT_NE(scan.cameraParams.fx(), scan.cameraParamsIntensity.fx());
  CSuperpixelMap map;
  ASSERT_TRUE(map.insertObservation(scan));
  const std::size_t n = map.patchCount();
  std::cout << "tests_rgbd.rawlog: " << n << " patches, depth fx " << scan.cameraParams.fx() << " intensity fx "
            << scan.cameraParamsIntensity.fx() << ", coverage "
            << map.views()[0].view.segmentation.stats.coverage() << "\n";
  // A 640x480 indoor frame at the default 40 cm^2 target area: hundreds of patches.
  EXPECT_GT(n, 50u);
  EXPECT_LT(n, 5000u);
  EXPECT_GT(map.views()[0].view.segmentation.stats.coverage(), 0.5);
  const auto& view = map.views()[0];
  EXPECT_EQ(view.view.projection.pinhole().fx, scan.cameraParams.fx());  // the range camera's own intrinsics
  ASSERT_EQ(view.patch_rgb.size(), n);
  // Colours come from the intensity image: not all the same.
  std::set<Rgb8> distinct(view.patch_rgb.begin(), view.patch_rgb.end());
  EXPECT_GT(distinct.size(), n / 4);
}

TEST(SuperpixelMap, SerializationRoundTripOfARealFrame) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  const auto ds = TumDataset::open(dir);
  CSuperpixelMap map;
  map.creationOptions.superpixels.target_patch_area_m2 = 0.005;
  map.likelihoodOptions.sigma_m = 0.03;
  map.renderOptions.style = CSuperpixelMap::TRenderOptions::Style::points;
  map.genericMapParams.enableObservationLikelihood = false;
  map.insertObservation(*tumObservation(ds, 0, true, someMount()), toCPose3D(someRobotPose()));
  map.insertObservation(*tumObservation(ds, 5, false, someMount()));
  const auto bytes = serialize(map);
  const auto object = deserialize(bytes);
  const auto copy = std::dynamic_pointer_cast<CSuperpixelMap>(object);
  ASSERT_TRUE(copy) << "deserialized a " << object->GetRuntimeClass()->className;
  EXPECT_EQ(copy->creationOptions.superpixels.target_patch_area_m2, 0.005);
  EXPECT_EQ(copy->likelihoodOptions.sigma_m, 0.03);
  EXPECT_EQ(copy->renderOptions.style, CSuperpixelMap::TRenderOptions::Style::points);
  EXPECT_FALSE(copy->genericMapParams.enableObservationLikelihood);
  ASSERT_EQ(copy->views().size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const auto &a = map.views()[i], &b = copy->views()[i];
    // The views' segmentation parameters (what the aligner's finer-scale retry re-segments with)
    // are the map's creation options, before and after the round trip.
    EXPECT_EQ(a.view.superpixels.target_patch_area_m2, 0.005);
    EXPECT_EQ(b.view.superpixels.target_patch_area_m2, 0.005);
    EXPECT_TRUE(a.T_map_camera.isApprox(b.T_map_camera, 0.0));
    EXPECT_EQ(a.view.projection.pinhole(), b.view.projection.pinhole());
    EXPECT_EQ(cv::norm(a.view.depth_m, b.view.depth_m, cv::NORM_INF), 0.0);
    EXPECT_EQ(cv::countNonZero(a.view.segmentation.labels != b.view.segmentation.labels), 0);
    ASSERT_EQ(a.view.segmentation.patches.size(), b.view.segmentation.patches.size());
    for (std::size_t k = 0; k < a.view.segmentation.patches.size(); ++k) {
      const auto &p = a.view.segmentation.patches[k], &q = b.view.segmentation.patches[k];
      EXPECT_EQ(p.centroid, q.centroid);
      EXPECT_EQ(p.normal, q.normal);
      EXPECT_EQ(p.area_m2, q.area_m2);
      EXPECT_EQ(p.covariance, q.covariance);
      EXPECT_EQ(p.bbox, q.bbox);
    }
    EXPECT_EQ(a.view.segmentation.adjacency, b.view.segmentation.adjacency);
    EXPECT_EQ(a.patch_rgb, b.patch_rgb);
    EXPECT_EQ(a.view.segmentation.stats.valid_pixels, b.view.segmentation.stats.valid_pixels);
  }
  // Serializing the copy gives the same bytes.
  EXPECT_EQ(serialize(*copy), bytes);
}

TEST(SuperpixelMap, CorruptSerializedMapGivesAnError) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  const auto ds = TumDataset::open(dir);
  CSuperpixelMap map;
  map.insertObservation(*tumObservation(ds, 0, true, someMount()));
  const auto bytes = serialize(map);
  // Truncated anywhere: an exception, never a crash or a half-read map.
  for (const double f : {0.001, 0.01, 0.1, 0.5, 0.9, 0.999}) {
    std::vector<std::uint8_t> cut(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(f * bytes.size()));
    EXPECT_THROW(deserialize(cut), std::exception) << "truncated at " << f;
  }
  // Overwritten bytes: an exception, or (if the damage happens to be harmless, e.g. in a depth
  // value) a map that is still consistent.
  std::mt19937 rng(7);
  int thrown = 0;
  for (int trial = 0; trial < 40; ++trial) {
    auto bad = bytes;
    const std::size_t at = 40 + rng() % (bytes.size() - 80);
    for (std::size_t k = 0; k < 8; ++k) bad[at + k] = 0xFF;
    try {
      const auto o = std::dynamic_pointer_cast<CSuperpixelMap>(deserialize(bad));
      ASSERT_TRUE(o);
      for (const auto& v : o->views()) EXPECT_NO_THROW(checkConsistency(v));
    } catch (const std::exception& e) {
      ++thrown;
      EXPECT_NE(std::string(e.what()).find("CSuperpixelMap"), std::string::npos) << e.what();
    }
  }
  EXPECT_GT(thrown, 0);
  std::cout << "corruption trials that threw: " << thrown << " of 40\n";
}

TEST(SuperpixelMap, CreatedFromIniByCMultiMetricMap) {
  const std::string ini =
      "[MappingApplication]\n"
      "superpixelMap_count=1\n"
      "[MappingApplication_superpixelMap_00_creationOpts]\n"
      "target_patch_area_m2=0.006\n"
      "min_patch_pixels=30\n"
      "enableObservationLikelihood=false\n"
      "[MappingApplication_superpixelMap_00_likelihoodOpts]\n"
      "sigma_m=0.05\n"
      "candidates=30\n"
      "[MappingApplication_superpixelMap_00_renderOpts]\n"
      "style=points\n";
  mrpt::maps::TSetOfMetricMapInitializers init;
  init.loadFromConfigFile(mrpt::config::CConfigFileMemory(ini), "MappingApplication");
  ASSERT_EQ(init.size(), 1u);
  mrpt::maps::CMultiMetricMap multi(init);
  const auto map = multi.mapByClass<CSuperpixelMap>();
  ASSERT_TRUE(map);
  EXPECT_EQ(map->creationOptions.superpixels.target_patch_area_m2, 0.006);
  EXPECT_EQ(map->creationOptions.superpixels.cleanup.min_patch_pixels, 30);
  EXPECT_EQ(map->likelihoodOptions.sigma_m, 0.05);
  EXPECT_EQ(map->likelihoodOptions.matching.associate.candidates, 30);
  EXPECT_EQ(map->renderOptions.style, CSuperpixelMap::TRenderOptions::Style::points);
  EXPECT_FALSE(map->genericMapParams.enableObservationLikelihood);

  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  const auto ds = TumDataset::open(dir);
  mrpt::obs::CSensoryFrame sf;
  sf.insert(tumObservation(ds, 0, true, someMount()));
  sf.insert(std::make_shared<mrpt::obs::CObservation2DRangeScan>());  // not for this map: ignored
  multi.insertObservation(*sf.getObservationByIndex(0));
  EXPECT_FALSE(map->insertObservation(*sf.getObservationByIndex(1)));
  EXPECT_EQ(map->views().size(), 1u);
  EXPECT_GT(map->patchCount(), 50u);
}

TEST(SuperpixelMap, BadIniParametersAreNamed) {
  auto load = [](const std::string& body) {
    mrpt::maps::TSetOfMetricMapInitializers init;
    init.loadFromConfigFile(mrpt::config::CConfigFileMemory("[M]\nsuperpixelMap_count=1\n" + body), "M");
  };
  EXPECT_NO_THROW(load(""));
  try {
    load("[M_superpixelMap_00_creationOpts]\ntarget_patch_area=0.004\n");
    ADD_FAILURE() << "unknown key accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("unknown key 'target_patch_area'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(load("[M_superpixelMap_00_creationOpts]\ntarget_patch_area_m2=abc\n"), std::exception);
  EXPECT_THROW(load("[M_superpixelMap_00_creationOpts]\ntarget_patch_area_m2=-1\n"), std::exception);
  EXPECT_THROW(load("[M_superpixelMap_00_likelihoodOpts]\nlambda=2\n"), std::exception);
  EXPECT_THROW(load("[M_superpixelMap_00_likelihoodOpts]\nsigma_m=0\n"), std::exception);
  EXPECT_THROW(load("[M_superpixelMap_00_renderOpts]\nstyle=cubes\n"), std::exception);
}

TEST(SuperpixelMap, BadObservationsGiveClearErrors) {
  CSuperpixelMap map;
  mrpt::obs::CObservation2DRangeScan laser;
  EXPECT_FALSE(map.insertObservation(laser));  // MRPT's contract: not for this map
  mrpt::obs::CObservation3DRangeScan no_range;
  EXPECT_THROW(map.insertObservation(no_range), std::exception);

  RgbdFrame f;
  f.depth_m = cv::Mat(480, 640, CV_32FC1, cv::Scalar(1.5f));
  f.rgb = cv::Mat(480, 640, CV_8UC3, cv::Scalar(10, 20, 30));
  f.rgb_intrinsics = f.depth_intrinsics;
  {
    auto obs = observationFromFrame(f);
    obs->cameraParams.ncols = 320;  // range image 640 wide, camera 320: inconsistent
    try {
      map.insertObservation(*obs);
      ADD_FAILURE() << "inconsistent depth intrinsics accepted";
    } catch (const std::exception& e) {
      EXPECT_NE(std::string(e.what()).find("640x480"), std::string::npos) << e.what();
    }
  }
  {
    auto obs = observationFromFrame(f);
    obs->cameraParamsIntensity.ncols = 1280;
    try {
      map.insertObservation(*obs);
      ADD_FAILURE() << "inconsistent intensity intrinsics accepted";
    } catch (const std::exception& e) {
      // Said by the observation's conversion (gasp::rawlog), before the map's own check.
      EXPECT_NE(std::string(e.what()).find("intensity image is 640x480 but cameraParamsIntensity say 1280x480"),
                std::string::npos)
          << e.what();
    }
  }
  {
    auto obs = observationFromFrame(f);
    obs->cameraParams.fx(0.0);
    EXPECT_THROW(map.insertObservation(*obs), std::exception);
  }
  EXPECT_TRUE(map.isEmpty());
  // A frame without valid depth is a valid, empty view.
  f.depth_m.setTo(0.0f);
  EXPECT_TRUE(map.insertObservation(*observationFromFrame(f)));
  EXPECT_EQ(map.patchCount(), 0u);
  // Likelihood of other observation types: refused clearly.
  EXPECT_FALSE(map.canComputeObservationLikelihood(laser));
}

TEST(SuperpixelMap, VisualisationAndFiles) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  const auto ds = TumDataset::open(dir);
  CSuperpixelMap map;
  map.insertObservation(*tumObservation(ds, 0, true, someMount()));
  const std::size_t n = map.patchCount();
  {
    mrpt::opengl::CSetOfObjects o;
    map.getVisualizationInto(o);
    auto tri = o.getByClass<mrpt::opengl::CSetOfTriangles>();
    ASSERT_TRUE(tri);
    EXPECT_EQ(tri->getTrianglesCount(), 16 * n);
  }
  map.renderOptions.style = CSuperpixelMap::TRenderOptions::Style::points;
  {
    mrpt::opengl::CSetOfObjects o;
    map.getVisualizationInto(o);
    auto pts = o.getByClass<mrpt::opengl::CPointCloudColoured>();
    ASSERT_TRUE(pts);
    EXPECT_GT(pts->size(), 20 * n);
  }
  map.renderOptions.style = CSuperpixelMap::TRenderOptions::Style::discs;
  const std::string prefix = gasp::test::scratchDir() + "/map";
  map.saveMetricMapRepresentationToFile(prefix);
  std::ifstream ply(prefix + "_patches.ply");
  ASSERT_TRUE(ply);
  std::string line;
  std::size_t vertices = 0, lines = 0;
  bool header = true;
  while (std::getline(ply, line)) {
    if (header) {
      if (line.rfind("element vertex ", 0) == 0) vertices = std::stoul(line.substr(15));
      if (line == "end_header") header = false;
    } else {
      ++lines;
    }
  }
  EXPECT_EQ(vertices, n);
  EXPECT_EQ(lines, n);
  std::ifstream table(prefix + "_patches.txt");
  std::size_t rows = 0;
  while (std::getline(table, line))
    if (!line.empty() && line[0] != '#') ++rows;
  EXPECT_EQ(rows, n);
  mrpt::opengl::COpenGLScene scene;
  ASSERT_TRUE(scene.loadFromFile(prefix + "_3D.3Dscene"));
  EXPECT_TRUE(scene.getByClass<mrpt::opengl::CSetOfTriangles>());
  EXPECT_THROW(map.saveMetricMapRepresentationToFile("/nonexistent/dir/map"), std::exception);
}

TEST(SuperpixelMap, LikelihoodReusesTheObservationAcrossPosesAndEqualsAFreshMap) {
  // A particle filter asks for one observation at many poses: the segmentation and associations
  // are computed once (a miss), each further pose is a hit. Every answer equals that of a copy of
  // the map (copies start with an empty cache), and anything the cached part depends on (the
  // depth pixels, the map's content, the association options) makes a miss.
  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  const auto ds = TumDataset::open(dir);
  const Isometry3 S = someMount();
  const Isometry3 P0 = *ds.frame(0).T_world_camera * S.inverse(), P4 = *ds.frame(4).T_world_camera * S.inverse();
  CSuperpixelMap map;
  map.insertObservation(*tumObservation(ds, 0, false, S), toCPose3D(P0));
  const auto obs = tumObservation(ds, 4, false, S);
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.03);
  std::vector<mrpt::poses::CPose3D> poses;
  for (int k = 0; k < 6; ++k) {
    Isometry3 jitter = Isometry3::Identity();
    jitter.translation() = Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    jitter.linear() = Eigen::AngleAxisd(noise(rng), Eigen::Vector3d::UnitZ()).toRotationMatrix();
    poses.push_back(toCPose3D(jitter * P4));
  }
  std::vector<double> cached;
  for (const auto& pose : poses) {
    cached.push_back(map.computeObservationLikelihood(*obs, pose));
    EXPECT_DOUBLE_EQ(cached.back(), CSuperpixelMap(map).computeObservationLikelihood(*obs, pose));
  }
  EXPECT_EQ(map.likelihoodCacheStats().misses, 1u);
  EXPECT_EQ(map.likelihoodCacheStats().hits, poses.size() - 1);
  EXPECT_GT(*std::max_element(cached.begin(), cached.end()), *std::min_element(cached.begin(), cached.end()))
      << "the poses must give different answers, or the test shows nothing";

  // Several threads at once (the likelihood is const): the same answers.
  std::vector<double> parallel(poses.size());
  {
    std::vector<std::thread> threads;
    for (std::size_t k = 0; k < poses.size(); ++k)
      threads.emplace_back([&, k] { parallel[k] = map.computeObservationLikelihood(*obs, poses[k]); });
    for (auto& t : threads) t.join();
  }
  for (std::size_t k = 0; k < poses.size(); ++k) EXPECT_DOUBLE_EQ(parallel[k], cached[k]);

  // sigma_m is applied per pose: a hit with a new answer, equal to a fresh map's.
  auto misses = map.likelihoodCacheStats().misses;
  map.likelihoodOptions.sigma_m = 0.05;
  EXPECT_DOUBLE_EQ(map.computeObservationLikelihood(*obs, poses[0]), CSuperpixelMap(map).computeObservationLikelihood(*obs, poses[0]));
  EXPECT_EQ(map.likelihoodCacheStats().misses, misses);

  // The same observation object with other depth pixels: a miss.
  auto changed = tumObservation(ds, 4, false, S);
  for (int r = 0; r < 240; ++r)
    for (int c = 0; c < 320; ++c) changed->rangeImage(r, c) = 0;
  const double ll_changed = map.computeObservationLikelihood(*changed, poses[0]);
  EXPECT_EQ(map.likelihoodCacheStats().misses, ++misses);
  EXPECT_DOUBLE_EQ(ll_changed, CSuperpixelMap(map).computeObservationLikelihood(*changed, poses[0]));
  EXPECT_NE(ll_changed, map.computeObservationLikelihood(*obs, poses[0]));
  EXPECT_EQ(map.likelihoodCacheStats().misses, ++misses);

  // The same pixels read with other units or from another sensor pose on the robot: a miss each.
  auto rescaled = tumObservation(ds, 4, false, S);
  rescaled->rangeUnits *= 1.02f;
  EXPECT_DOUBLE_EQ(map.computeObservationLikelihood(*rescaled, poses[0]),
                   CSuperpixelMap(map).computeObservationLikelihood(*rescaled, poses[0]));
  EXPECT_EQ(map.likelihoodCacheStats().misses, ++misses);
  const double ll_obs = map.computeObservationLikelihood(*obs, poses[0]);  // the cache holds obs again
  EXPECT_EQ(map.likelihoodCacheStats().misses, ++misses);
  Isometry3 S2 = S;
  S2.translation().x() += 0.1;
  const auto remounted = tumObservation(ds, 4, false, S2);
  const double ll_remounted = map.computeObservationLikelihood(*remounted, poses[0]);
  EXPECT_EQ(map.likelihoodCacheStats().misses, ++misses);
  EXPECT_DOUBLE_EQ(ll_remounted, CSuperpixelMap(map).computeObservationLikelihood(*remounted, poses[0]));
  EXPECT_NE(ll_remounted, ll_obs);

  // A range image stored in an external file (not in memory until the scan is loaded): the
  // same answer as the scan in memory, and a further pose is a hit.
  const std::string external_dir = gasp::test::scratchDir() + "/likelihood_external";
  std::filesystem::create_directories(external_dir);
  auto external = tumObservation(ds, 4, false, S);
  external->rangeImage_convertToExternalStorage(external_dir + "/range_4.bin", external_dir + "/");  // absolute: no lazy-load base
  ASSERT_TRUE(external->rangeImage_isExternallyStored());
  external->unload();
  ASSERT_EQ(external->rangeImage.size(), 0) << "the test needs the range image out of memory";
  EXPECT_DOUBLE_EQ(map.computeObservationLikelihood(*external, poses[0]), ll_obs);
  EXPECT_EQ(map.likelihoodCacheStats().misses, ++misses);
  const auto hits = map.likelihoodCacheStats().hits;
  EXPECT_DOUBLE_EQ(map.computeObservationLikelihood(*external, poses[1]),
                   CSuperpixelMap(map).computeObservationLikelihood(*obs, poses[1]));
  EXPECT_EQ(map.likelihoodCacheStats().hits, hits + 1);
  // Out of memory again and asked from several threads at once: one loads, none reads a half-loaded image.
  external->unload();
  std::vector<double> from_threads(4);
  {
    std::vector<std::thread> threads;
    for (std::size_t k = 0; k < from_threads.size(); ++k)
      threads.emplace_back([&, k] { from_threads[k] = map.computeObservationLikelihood(*external, poses[k]); });
    for (auto& t : threads) t.join();
  }
  for (std::size_t k = 0; k < from_threads.size(); ++k)
    EXPECT_DOUBLE_EQ(from_threads[k], CSuperpixelMap(map).computeObservationLikelihood(*obs, poses[k])) << k;
  misses = map.likelihoodCacheStats().misses;

  // A colour image that cannot be loaded (its external file is gone): the likelihood needs depth
  // alone, so it answers as for the scan without colour.
  auto coloured = tumObservation(ds, 4, true, S);
  ASSERT_TRUE(coloured->hasIntensityImage);
  coloured->intensityImage.setExternalStorage(external_dir + "/no_such_rgb.png");
  EXPECT_DOUBLE_EQ(map.computeObservationLikelihood(*coloured, poses[0]), ll_obs);
  misses = map.likelihoodCacheStats().misses;

  // Segmentation options: a miss.
  map.creationOptions.superpixels.target_patch_area_m2 *= 1.5;
  EXPECT_DOUBLE_EQ(map.computeObservationLikelihood(*obs, poses[0]), CSuperpixelMap(map).computeObservationLikelihood(*obs, poses[0]));
  EXPECT_EQ(map.likelihoodCacheStats().misses, ++misses);

  // Association options: a miss.
  map.likelihoodOptions.matching.associate.lambda = 0.3;
  EXPECT_DOUBLE_EQ(map.computeObservationLikelihood(*obs, poses[0]), CSuperpixelMap(map).computeObservationLikelihood(*obs, poses[0]));
  EXPECT_EQ(map.likelihoodCacheStats().misses, ++misses);

  // New content in the map: a miss, and the new view counts.
  map.insertObservation(*tumObservation(ds, 8, false, S), toCPose3D(*ds.frame(8).T_world_camera * S.inverse()));
  EXPECT_DOUBLE_EQ(map.computeObservationLikelihood(*obs, poses[0]), CSuperpixelMap(map).computeObservationLikelihood(*obs, poses[0]));
  EXPECT_EQ(map.likelihoodCacheStats().misses, ++misses);
  map.clear();
  EXPECT_EQ(map.computeObservationLikelihood(*obs, poses[0]), 0.0);  // empty: no information
}

TEST(SuperpixelMap, MatchingRatioAndLikelihoodPreferTheTruePose) {
  GASP_REQUIRE_DATA(dir, "tum/fr1_desk9");
  const auto ds = TumDataset::open(dir);
  const Isometry3 S = someMount();
  const Isometry3 W0 = *ds.frame(0).T_world_camera, W4 = *ds.frame(4).T_world_camera;
  // Robot poses in the world such that the cameras are where TUM's ground truth says.
  const Isometry3 P0 = W0 * S.inverse(), P4 = W4 * S.inverse();
  CSuperpixelMap m0, m4;
  m0.insertObservation(*tumObservation(ds, 0, true, S), toCPose3D(P0));
  m4.insertObservation(*tumObservation(ds, 4, true, S));  // map 4 in its own robot frame
  Isometry3 off = Isometry3::Identity();
  off.translation() = Eigen::Vector3d(0.15, 0.0, 0.0);
  mrpt::maps::TMatchingRatioParams mp;
  const float right = m0.compute3DMatchingRatio(&m4, toCPose3D(P4), mp);
  const float wrong = m0.compute3DMatchingRatio(&m4, toCPose3D(off * P4), mp);
  std::cout << "matching ratio at the true pose " << right << ", 15 cm off " << wrong << "\n";
  EXPECT_GT(right, 0.05f);
  EXPECT_GT(right, 2 * wrong);
  const auto obs4 = tumObservation(ds, 4, false, S);
  const double ll_right = m0.computeObservationLikelihood(*obs4, toCPose3D(P4));
  const double ll_wrong = m0.computeObservationLikelihood(*obs4, toCPose3D(off * P4));
  std::cout << "log-likelihood at the true pose " << ll_right << ", 15 cm off " << ll_wrong << "\n";
  EXPECT_GT(ll_right, ll_wrong);
  EXPECT_LE(ll_right, 0.0);
  EXPECT_GE(ll_wrong, -4.5);
  mrpt::obs::CObservation2DRangeScan laser;
  EXPECT_FALSE(m0.canComputeObservationLikelihood(laser));
  EXPECT_GT(m0.compute3DMatchingRatio(&m0, toCPose3D(Isometry3::Identity()), mp), 0.5f);  // itself
  // MRPT adds every map's answer for every observation of a sensory frame without asking
  // canComputeObservationLikelihood: other observation types and an empty map answer 0.
  EXPECT_EQ(m0.computeObservationLikelihood(laser, toCPose3D(P4)), 0.0);
  EXPECT_EQ(CSuperpixelMap().computeObservationLikelihood(*obs4, toCPose3D(P4)), 0.0);
  mrpt::obs::CSensoryFrame sf;
  sf.insert(obs4);
  sf.insert(std::make_shared<mrpt::obs::CObservation2DRangeScan>());
  EXPECT_DOUBLE_EQ(m0.computeObservationsLikelihood(sf, toCPose3D(P4)), ll_right);
  // CMultiMetricMap passes the other multi-map itself to each of its maps: the superpixel map
  // inside it is used, as if it were passed alone.
  mrpt::maps::CMultiMetricMap multi4;
  multi4.maps.push_back(std::make_shared<CSuperpixelMap>(m4));
  EXPECT_EQ(m0.compute3DMatchingRatio(&multi4, toCPose3D(P4), mp), right);
  std::string why;
  EXPECT_EQ(CSuperpixelMap::findIn(&multi4), multi4.maps[0].get());
  multi4.maps.push_back(std::make_shared<CSuperpixelMap>(m4));
  EXPECT_FALSE(CSuperpixelMap::findIn(&multi4, &why));
  EXPECT_NE(why.find("holding 2 gasp::CSuperpixelMap"), std::string::npos) << why;
  EXPECT_EQ(m0.compute3DMatchingRatio(&multi4, toCPose3D(P4), mp), 0.0f);
}

// A map of LiDAR sweeps and a sweep seen from a pose, as a particle filter asks: the true pose is
// the most likely of the ones tried, as a rotating scan and as a point cloud; the pose-free part
// is computed once per observation; depth scans get no information from a map of sweeps.
TEST(SuperpixelMap, LikelihoodOfALidarSweepPrefersTheTruePose) {
  const sim::Scene room = sim::makeScene("room");
  const sim::LidarSensor lidar = sim::lidarSensor(16);
  Isometry3 S = Isometry3::Identity();  // the LiDAR 0.8 m up on the robot
  S.translation() = Eigen::Vector3d(0.1, 0.0, 0.8);
  auto robotAt = [](double x, double y, double yaw_deg) {
    Isometry3 P = Isometry3::Identity();
    P.linear() = Eigen::AngleAxisd(yaw_deg * M_PI / 180, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    P.translation() = Eigen::Vector3d(x, y, 0.2);
    return P;
  };
  CSuperpixelMap map;
  int frame = 0;
  for (const Isometry3& P : {robotAt(0.0, 0.0, 0.0), robotAt(0.8, 0.3, 40.0), robotAt(-0.5, 0.6, -70.0)}) {
    auto sweep = toRotatingScan(sim::simulateLidarScan(room, lidar, P * S, 1, frame++), "LIDAR");
    sweep.setSensorPose(toCPose3D(S));
    ASSERT_TRUE(map.insertObservation(sweep, toCPose3D(P)));
  }
  const Isometry3 P = robotAt(0.3, 0.2, 15.0);
  const RangeScan seen = sim::simulateLidarScan(room, lidar, P * S, 1, frame);
  auto rotating = toRotatingScan(seen, "LIDAR");
  rotating.setSensorPose(toCPose3D(S));
  auto cloud = toPointCloud(seen, "CLOUD");
  cloud.setSensorPose(toCPose3D(S));
  auto points = toPointsScan(seen, "POINTS");  // a 3D scan of the sweep's points alone
  points.setSensorPose(toCPose3D(S));
  for (const mrpt::obs::CObservation* obs : {static_cast<const mrpt::obs::CObservation*>(&rotating),
                                             static_cast<const mrpt::obs::CObservation*>(&cloud),
                                             static_cast<const mrpt::obs::CObservation*>(&points)}) {
    EXPECT_TRUE(map.canComputeObservationLikelihood(*obs));
    const auto before = map.likelihoodCacheStats();
    const double right = map.computeObservationLikelihood(*obs, toCPose3D(P));
    std::cout << obs->GetRuntimeClass()->className << ": log-likelihood at the true pose " << right;
    for (const Isometry3& off : {robotAt(0.3, 0.0, 0.0), robotAt(0.0, 0.0, 10.0), robotAt(0.0, 0.15, 0.0)}) {
      const double wrong = map.computeObservationLikelihood(*obs, toCPose3D(P * off));
      std::cout << ", " << wrong;
      EXPECT_GT(right, wrong + 1.0);  // by more than a nat in the mean over the sweep's patches
    }
    std::cout << "\n";
    EXPECT_LE(right, 0.0);
    const auto after = map.likelihoodCacheStats();
    EXPECT_EQ(after.misses, before.misses + 1);  // segmented and associated once
    EXPECT_EQ(after.hits, before.hits + 3);
  }
  // The cache keys on the points: another sweep with the same label, time and mount misses.
  const auto before = map.likelihoodCacheStats();
  auto other = toPointCloud(sim::simulateLidarScan(room, lidar, robotAt(-0.4, 0.5, -60.0) * S, 1, frame + 1), "CLOUD");
  other.setSensorPose(toCPose3D(S));
  other.timestamp = cloud.timestamp;
  const double other_ll = map.computeObservationLikelihood(other, toCPose3D(P));
  EXPECT_EQ(map.likelihoodCacheStats().misses, before.misses + 1);
  EXPECT_NE(other_ll, map.computeObservationLikelihood(cloud, toCPose3D(P)));
  auto other_points = toPointsScan(sim::simulateLidarScan(room, lidar, robotAt(-0.4, 0.5, -60.0) * S, 1, frame + 1), "POINTS");
  other_points.setSensorPose(toCPose3D(S));
  other_points.timestamp = points.timestamp;
  const auto misses = map.likelihoodCacheStats().misses;
  EXPECT_NE(map.computeObservationLikelihood(other_points, toCPose3D(P)),
            map.computeObservationLikelihood(points, toCPose3D(P)));
  EXPECT_EQ(map.likelihoodCacheStats().misses, misses + 2);
  // Another sensor's cloud (no rings) is not for this map: not inserted, no information.
  auto blob = mrpt::maps::CSimplePointsMap::Create();
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-3.0f, 3.0f);
  for (int i = 0; i < 5000; ++i) blob->insertPoint(u(rng), u(rng), u(rng));
  mrpt::obs::CObservationPointCloud stereo;
  stereo.pointcloud = blob;
  CSuperpixelMap unchanged = map;
  EXPECT_FALSE(unchanged.insertObservation(stereo));
  EXPECT_EQ(unchanged.views().size(), 3u);
  EXPECT_EQ(map.computeObservationLikelihood(stereo, toCPose3D(P)), 0.0);
  mrpt::obs::CObservation3DRangeScan stereo_points;  // the same as a 3D scan of points alone
  stereo_points.hasRangeImage = false;
  stereo_points.resizePoints3DVectors(blob->size());
  for (std::size_t i = 0; i < blob->size(); ++i)
    blob->getPoint(i, stereo_points.points3D_x[i], stereo_points.points3D_y[i], stereo_points.points3D_z[i]);
  stereo_points.hasPoints3D = true;
  EXPECT_FALSE(unchanged.insertObservation(stereo_points));
  EXPECT_EQ(unchanged.views().size(), 3u);
  EXPECT_EQ(map.computeObservationLikelihood(stereo_points, toCPose3D(P)), 0.0);
  // Depth scans get no information from a map of sweeps, and sweeps none from a map of depth images.
  RgbdFrame f;
  f.depth_m = cv::Mat(480, 640, CV_32FC1, cv::Scalar(2.0f));
  const auto depth = observationFromFrame(f);
  EXPECT_FALSE(map.canComputeObservationLikelihood(*depth));
  EXPECT_EQ(map.computeObservationLikelihood(*depth, toCPose3D(P)), 0.0);
  CSuperpixelMap depth_map;
  ASSERT_TRUE(depth_map.insertObservation(*depth));
  EXPECT_FALSE(depth_map.canComputeObservationLikelihood(rotating));
  EXPECT_EQ(depth_map.computeObservationLikelihood(rotating, toCPose3D(P)), 0.0);
}

// A map of sweeps reads back with each sweep's normals as they were made: the grown windows'
// noise (lidar.returns_normal_growth) and the plane tolerance (the last gate, 4 range sigmas) are
// written with the view (serialization version 3), so the normals fitted again on reading are the
// same, also with another range noise. A version 2 sweep record (without the two) reads with
// adjacent rows and the default last gate, as such a map was made.
TEST(SuperpixelMap, SweepsReadBackWithTheirOwnNormals) {
  const sim::Scene room = sim::makeScene("room");
  Isometry3 P = Isometry3::Identity();
  P.translation() = Eigen::Vector3d(0.2, 0.1, 1.0);
  const auto sweep = toRotatingScan(sim::simulateLidarScan(room, sim::lidarSensor(64), P, 1, 0), "LIDAR");
  // The map's sweep, and the same sweep read back from `bytes`: their normals, how many differ.
  auto readBack = [](const CSuperpixelMap& map, const std::vector<std::uint8_t>& bytes, int& with_normal) {
    const auto copy = std::dynamic_pointer_cast<CSuperpixelMap>(deserialize(bytes));
    if (!copy || copy->views().size() != 1u) return -1;
    const auto& made = *map.views().at(0).view.returns;
    const auto& again = *copy->views().at(0).view.returns;
    EXPECT_EQ(again.normalNoise(), made.normalNoise());
    EXPECT_EQ(again.planeTolerance(), made.planeTolerance());
    int differ = 0;
    with_normal = 0;
    for (int i = 0; i < made.rows() * made.cols(); ++i) {
      with_normal += made.normal(i).isZero() ? 0 : 1;
      differ += made.normal(i) == again.normal(i) ? 0 : 1;
    }
    return differ;
  };
  {
    CSuperpixelMap map;
    map.creationOptions.lidar.returns_normal_growth = true;
    map.creationOptions.lidar.range_sigma_m = 0.03;  // another noise: another last gate
    ASSERT_TRUE(map.insertObservation(sweep));
    EXPECT_DOUBLE_EQ(map.views().at(0).view.returns->normalNoise(), 0.03);
    const auto bytes = serialize(map);
    int with_normal = 0;
    EXPECT_EQ(readBack(map, bytes, with_normal), 0);
    EXPECT_GT(with_normal, 10000);
    EXPECT_EQ(serialize(*std::dynamic_pointer_cast<CSuperpixelMap>(deserialize(bytes))), bytes);
  }
  {  // version 2: the record without the noise and the tolerance (two doubles before the end flag)
    CSuperpixelMap map;
    map.creationOptions.lidar.returns_normal_growth = false;  // as a version 2 map's sweeps were made
    ASSERT_TRUE(map.insertObservation(sweep));
    auto bytes = serialize(map);
    const std::string name = "gasp::CSuperpixelMap";
    const auto at = std::search(bytes.begin(), bytes.end(), name.begin(), name.end());
    ASSERT_NE(at, bytes.end());
    const std::size_t version_byte = static_cast<std::size_t>(at - bytes.begin()) + name.size();
    ASSERT_EQ(bytes[version_byte], 3);
    bytes[version_byte] = 2;
    bytes.erase(bytes.end() - 1 - 2 * static_cast<std::ptrdiff_t>(sizeof(double)), bytes.end() - 1);
    int with_normal = 0;
    EXPECT_EQ(readBack(map, bytes, with_normal), 0);
    EXPECT_GT(with_normal, 100);
  }
}

TEST(SuperpixelMapView, ColoursOfADistortedRegisteredFrameComeFromTheSamePixels) {
  // A registered RGB-D frame whose cameras both carry fr1's lens distortion: the view's depth is
  // resampled to the pinhole camera (makeDepthView), so the colour image must be too, or the
  // colours come from pixels several px away at the corners. The colour image encodes each
  // pixel's position (R = u / 2.5, G = v / 2.5), so a patch's colour says where it was looked up.
  const auto k = CameraIntrinsics::tumFreiburg1();
  RgbdFrame f;
  f.depth_intrinsics = f.rgb_intrinsics = k;
  f.depth_m = cv::Mat(k.height, k.width, CV_32FC1, cv::Scalar(1.5f));
  f.depth_m(cv::Rect(200, 150, 200, 150)).setTo(1.2f);  // a box in front, so there are edges
  f.rgb = cv::Mat(k.height, k.width, CV_8UC3);
  for (int v = 0; v < k.height; ++v)
    for (int u = 0; u < k.width; ++u)
      f.rgb.at<cv::Vec3b>(v, u) = cv::Vec3b(0, static_cast<std::uint8_t>(v / 2.5), static_cast<std::uint8_t>(u / 2.5));
  const SuperpixelMapView view = makeMapView(f, Isometry3::Identity(), SuperpixelParams{});
  for (double c : view.view.projection.pinhole().distortion) EXPECT_EQ(c, 0.0);
  const auto& seg = view.view.segmentation;
  ASSERT_EQ(view.patch_rgb.size(), seg.patches.size());
  // Expected: the mean over each patch's pixels (every 2nd, as sampled) of the resampled image;
  // the colour as stored at the same pixels is the wrong answer.
  const cv::Mat undistorted = Undistortion(k).applyToImage(f.rgb);
  std::vector<Eigen::Vector3d> right(seg.patches.size(), Eigen::Vector3d::Zero()), wrong = right;
  std::vector<int> count(seg.patches.size(), 0);
  for (int v = 0; v < seg.labels.rows; v += 2)
    for (int u = 0; u < seg.labels.cols; u += 2) {
      const int l = seg.labels.at<int>(v, u);
      if (l < 0) continue;
      const cv::Vec3b a = undistorted.at<cv::Vec3b>(v, u), b = f.rgb.at<cv::Vec3b>(v, u);
      right[static_cast<std::size_t>(l)] += Eigen::Vector3d(a[2], a[1], a[0]);
      wrong[static_cast<std::size_t>(l)] += Eigen::Vector3d(b[2], b[1], b[0]);
      ++count[static_cast<std::size_t>(l)];
    }
  int checked = 0, distinct = 0;
  for (std::size_t i = 0; i < seg.patches.size(); ++i) {
    if (count[i] < 20) continue;
    const Eigen::Vector3d got(view.patch_rgb[i][0], view.patch_rgb[i][1], view.patch_rgb[i][2]);
    const Eigen::Vector3d r = right[i] / count[i], w = wrong[i] / count[i];
    EXPECT_LT((got - r).cwiseAbs().maxCoeff(), 1.01) << "patch " << i;
    ++checked;
    distinct += (r - w).cwiseAbs().maxCoeff() > 3.0;  // corners: the lens moves pixels by > 7 px
  }
  EXPECT_GT(checked, 100);
  EXPECT_GT(distinct, 10);  // the test can tell the two lookups apart
}
