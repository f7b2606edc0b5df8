// Bad rawlogs and bad program input give a gasp::Error (or an "error:" exit) that says what is wrong.
#include <gtest/gtest.h>
#include <mrpt/core/Clock.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/io/CFileOutputStream.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/serialization/CArchive.h>

#include <opencv2/imgcodecs.hpp>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/rawlog/rawlog_entries.h"
#include "gasp/rawlog/rawlog_reader.h"
#include "gasp/rawlog/rawlog_writer.h"
#include "gasp_test_data.h"
#include "rawlog_test_frames.h"

namespace {

/// The gasp::Error message of reading the whole rawlog, or "" when it did not throw.
std::string readError(const std::string& path) {
  try {
    gasp::readRawlogFrames(path);
  } catch (const gasp::Error& e) {
    return e.what();
  }
  return "";
}

/// A 4 x 3 scan at 1.234 m (rangeUnits 1 mm).
mrpt::obs::CObservation3DRangeScan tinyScan() {
  mrpt::obs::CObservation3DRangeScan scan;
  scan.hasRangeImage = true;
  scan.cameraParams.ncols = 4;
  scan.cameraParams.nrows = 3;
  scan.cameraParams.setIntrinsicParamsFromValues(5.0, 5.0, 1.5, 1.0);
  scan.rangeImage_setSize(3, 4);
  scan.rangeImage.fill(1234);
  scan.rangeUnits = 0.001f;
  return scan;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

TEST(RawlogErrors, MissingEmptyAndGarbageFiles) {
  const std::string dir = gasp::test::scratchDir();
  std::string msg = readError(dir + "/missing.rawlog");
  EXPECT_TRUE(contains(msg, "missing.rawlog") && contains(msg, "not found")) << msg;

  std::ofstream(dir + "/empty.rawlog").close();
  msg = readError(dir + "/empty.rawlog");
  EXPECT_TRUE(contains(msg, "empty.rawlog") && contains(msg, "empty")) << msg;

  {
    std::ofstream f(dir + "/garbage.rawlog", std::ios::binary);
    for (int i = 0; i < 5000; ++i) f << static_cast<char>((i * 7919 + 13) % 251);
  }
  msg = readError(dir + "/garbage.rawlog");
  EXPECT_TRUE(contains(msg, "garbage.rawlog") && contains(msg, "not an MRPT rawlog")) << msg;

  std::ofstream(dir + "/text.rawlog") << "timestamp x y z\n1 2 3 4\n";
  msg = readError(dir + "/text.rawlog");
  EXPECT_TRUE(contains(msg, "text.rawlog") && contains(msg, "not an MRPT rawlog")) << msg;

  msg = readError(dir);
  EXPECT_TRUE(contains(msg, "directory")) << msg;
}

TEST(RawlogErrors, RawlogWithoutRangeScansSaysWhatItHolds) {
  const std::string path = gasp::test::scratchDir() + "/odometry.rawlog";
  {
    mrpt::io::CFileGZOutputStream out(path);
    auto ar = mrpt::serialization::archiveFrom(out);
    for (int i = 0; i < 3; ++i) {
      mrpt::obs::CObservationOdometry odo;
      odo.timestamp = mrpt::Clock::fromDouble(10.0 + i);
      odo.sensorLabel = "ODOMETRY";
      ar << odo;
    }
  }
  const std::string msg = readError(path);
  EXPECT_TRUE(contains(msg, "odometry.rawlog") && contains(msg, "no CObservation3DRangeScan") &&
              contains(msg, "3 x CObservationOdometry"))
      << msg;
}

TEST(RawlogErrors, OtherObservationsAreSkippedAndCounted) {
  const std::string path = gasp::test::scratchDir() + "/mixed.rawlog";
  {
    mrpt::io::CFileGZOutputStream out(path);
    auto ar = mrpt::serialization::archiveFrom(out);
    mrpt::obs::CObservationOdometry odo;
    ar << odo;
    ar << tinyScan() << odo;
  }
  gasp::RawlogReader reader(path);
  const auto f = reader.next();
  ASSERT_TRUE(f.has_value());
  EXPECT_FLOAT_EQ(f->depth_m.at<float>(2, 3), 1.234f);
  EXPECT_DOUBLE_EQ(f->depth_units_per_metre, 1000.0);
  EXPECT_FALSE(reader.next().has_value());
  EXPECT_EQ(reader.skipped().at("CObservationOdometry"), 2u);
}

TEST(RawlogErrors, ScanWithoutRangeImage) {
  const std::string path = gasp::test::scratchDir() + "/norange.rawlog";
  {
    mrpt::io::CFileGZOutputStream out(path);
    auto ar = mrpt::serialization::archiveFrom(out);
    mrpt::obs::CObservation3DRangeScan scan;
    scan.sensorLabel = "TOF";
    ar << scan;
  }
  const std::string msg = readError(path);
  EXPECT_TRUE(contains(msg, "norange.rawlog") && contains(msg, "no range image")) << msg;
}

TEST(Tum2RawlogProgram, MissingTumFolderFailsWithError) {
  const std::string program = std::string(GASP_BIN_DIR) + "/gasp-tum2rawlog";
  ASSERT_TRUE(std::filesystem::exists(program)) << program;
  const std::string dir = gasp::test::scratchDir();
  const std::string cmd = "'" + program + "' '" + dir + "/no_such_tum' '" + dir +
                          "/out.rawlog' 2> '" + dir + "/stderr.txt'";
  const int status = std::system(cmd.c_str());
  EXPECT_NE(status, 0);
  std::ifstream err(dir + "/stderr.txt");
  const std::string text((std::istreambuf_iterator<char>(err)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text.rfind("error: ", 0), 0u) << text;
  EXPECT_TRUE(contains(text, "no_such_tum")) << text;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out.rawlog"));

  // Bad option values are rejected too.
  const std::string bad = "'" + program + "' '" + dir + "' '" + dir + "/x.rawlog' --format 3 2>/dev/null";
  EXPECT_NE(std::system(bad.c_str()), 0);
}

TEST(Tum2RawlogProgram, ConvertsFr1Desk9) {
  GASP_REQUIRE_DATA(tum, "tum/fr1_desk9");
  const std::string program = std::string(GASP_BIN_DIR) + "/gasp-tum2rawlog";
  const std::string dir = gasp::test::scratchDir();
  const std::string cmd = "'" + program + "' '" + tum + "' '" + dir +
                          "/d.rawlog' --format 1 --max-frames 5 --intrinsics fr1 > '" + dir +
                          "/stdout.txt'";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  std::ifstream out(dir + "/stdout.txt");
  const std::string text((std::istreambuf_iterator<char>(out)), std::istreambuf_iterator<char>());
  EXPECT_TRUE(contains(text, "frames written:      5")) << text;
  EXPECT_TRUE(contains(text, "d_groundtruth.txt")) << text;
  EXPECT_EQ(gasp::readRawlogFrames(dir + "/d.rawlog").size(), 5u);
}

TEST(RawlogErrors, TruncatedRawlogIsReportedAsCorrupt) {
  const std::string dir = gasp::test::scratchDir();
  const std::string path = dir + "/cut.rawlog";
  {
    gasp::RawlogWriter writer(path, {gasp::RawlogFormat::Observations, false, 0});  // plain
    for (int i = 0; i < 3; ++i) writer.write(gasp::test::syntheticFrame(1.0 + i));
  }
  const auto size = std::filesystem::file_size(path);
  std::filesystem::resize_file(path, size * 5 / 6);  // cut inside the third observation
  gasp::RawlogReader reader(path);
  EXPECT_TRUE(reader.next().has_value());
  EXPECT_TRUE(reader.next().has_value());
  try {
    reader.next();
    FAIL() << "expected gasp::Error for the truncated third observation";
  } catch (const gasp::Error& e) {
    EXPECT_TRUE(contains(e.what(), "cut.rawlog") && contains(e.what(), "truncated")) << e.what();
  }
}

namespace {

/// The gasp::Error message of reading every entry of the rawlog, or "" when it did not throw;
/// optionally the entries read and, after a whole read, endedAfterAction() and objectsRead().
std::string entriesError(const std::string& path, std::size_t* entries_read = nullptr,
                         bool* ended_after_action = nullptr, std::size_t* objects_read = nullptr) {
  std::size_t count = 0;
  try {
    gasp::RawlogEntries entries(path);
    while (entries.next()) ++count;
    if (ended_after_action) *ended_after_action = entries.endedAfterAction();
    if (objects_read) *objects_read = entries.objectsRead();
  } catch (const gasp::Error& e) {
    if (entries_read) *entries_read = count;
    return e.what();
  }
  if (entries_read) *entries_read = count;
  return "";
}

}  // namespace

TEST(RawlogEntries, ReadsBothFormatsAsMrptsEngineDoes) {
  const std::string dir = gasp::test::scratchDir();
  for (const auto format : {gasp::RawlogFormat::ActionsSensoryFrames, gasp::RawlogFormat::Observations}) {
    const std::string path = dir + "/f" + std::to_string(static_cast<int>(format)) + ".rawlog";
    {
      gasp::RawlogWriter writer(path, {format, false, 1});
      for (int i = 0; i < 3; ++i) writer.write(gasp::test::syntheticFrame(1.0 + i));
    }
    gasp::RawlogEntries entries(path);
    for (int i = 0; i < 3; ++i) {
      const auto entry = entries.next();
      ASSERT_TRUE(entry.has_value()) << i;
      if (format == gasp::RawlogFormat::ActionsSensoryFrames) {
        ASSERT_TRUE(entry->action && entry->observations) << i;
        EXPECT_FALSE(entry->observation);
        EXPECT_EQ(entry->observations->size(), 1u);
        EXPECT_EQ(entries.objectsRead(), 2u * (i + 1));
      } else {
        ASSERT_TRUE(entry->observation) << i;
        EXPECT_FALSE(entry->action || entry->observations);
        EXPECT_EQ(entries.objectsRead(), i + 1u);
      }
    }
    EXPECT_FALSE(entries.next().has_value());
    EXPECT_FALSE(entries.next().has_value());  // the end stays the end
  }
}

TEST(RawlogEntries, TruncatedFilesAreErrorsNotAnEarlyEnd) {
  // MRPT's getActionObservationPairOrObservation() reads a cut file as a shorter one; here the
  // cut is an error, compressed or plain, whichever format.
  const std::string dir = gasp::test::scratchDir();
  for (const int level : {0, 1}) {
    for (const auto format : {gasp::RawlogFormat::ActionsSensoryFrames, gasp::RawlogFormat::Observations}) {
      const std::string path = dir + "/cut_" + std::to_string(level) + "_" + std::to_string(static_cast<int>(format)) + ".rawlog";
      {
        gasp::RawlogWriter writer(path, {format, false, level});
        for (int i = 0; i < 3; ++i) writer.write(gasp::test::syntheticFrame(1.0 + i));
      }
      std::filesystem::resize_file(path, std::filesystem::file_size(path) * 5 / 6);
      std::size_t read = 0;
      const std::string msg = entriesError(path, &read);
      EXPECT_TRUE(contains(msg, path) && contains(msg, "truncated")) << level << ' ' << msg;
      // Plain: the two whole entries before the cut; compressed, the cut falls earlier.
      if (level == 0) {
        EXPECT_EQ(read, 2u) << msg;
      }
      EXPECT_LT(read, 3u) << level << ' ' << msg;
      // GASP's scan reader says the same.
      EXPECT_TRUE(contains(readError(path), "truncated")) << level << ' ' << readError(path);
    }
  }
  // Cut anywhere: plain files at tenths of their length, gzip files likewise and without their
  // 8-byte trailer (MRPT's reader takes all of these for the end of the file).
  for (const int level : {0, 1}) {
    const std::string whole = dir + "/whole_" + std::to_string(level) + ".rawlog";
    {
      gasp::RawlogWriter writer(whole, {gasp::RawlogFormat::Observations, false, level});
      for (int i = 0; i < 3; ++i) writer.write(gasp::test::syntheticFrame(1.0 + i));
    }
    const auto size = std::filesystem::file_size(whole);
    std::vector<std::uintmax_t> cuts;
    for (int tenth = 1; tenth < 10; ++tenth) cuts.push_back(size * tenth / 10);
    cuts.push_back(size - 1);
    if (level > 0) cuts.push_back(size - 8);  // no gzip trailer
    for (const auto cut : cuts) {
      const std::string path = dir + "/cut.rawlog";
      std::filesystem::copy_file(whole, path, std::filesystem::copy_options::overwrite_existing);
      std::filesystem::resize_file(path, cut);
      std::size_t read = 0;
      const std::string msg = entriesError(path, &read);
      EXPECT_TRUE(contains(msg, "truncated") || contains(msg, "empty")) << level << " cut at " << cut << ": " << msg;
      // A gzip file cut in its trailer holds every entry; the error comes after the last.
      if (level == 0 || cut < size - 8) {
        EXPECT_LT(read, 3u) << level << " cut at " << cut;
      }
    }
  }
  {
    // A gzip file whose checksum fails (its content may be damaged anywhere).
    const std::string path = dir + "/crc.rawlog";
    std::filesystem::copy_file(dir + "/whole_1.rawlog", path);
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(std::filesystem::file_size(path) - 8));
    f.put('\x5a');
    f.close();
    const std::string msg = entriesError(path);
    EXPECT_TRUE(contains(msg, "corrupt or truncated gzip stream")) << msg;
    EXPECT_TRUE(contains(readError(path), "corrupt or truncated gzip stream")) << readError(path);
  }
  // A format-#1 file that ends after an action, without its sensory frame: the end of the file,
  // as in MRPT's own reader (MRPT's sample kf-slam_demo.rawlog ends that way), not an error.
  const std::string path = dir + "/action_last.rawlog";
  {
    mrpt::io::CFileGZOutputStream out(path);
    auto ar = mrpt::serialization::archiveFrom(out);
    mrpt::obs::CActionCollection action;
    mrpt::obs::CSensoryFrame sf;
    sf.insert(std::make_shared<mrpt::obs::CObservation3DRangeScan>(tinyScan()));
    ar << action << sf << action;
  }
  std::size_t entries = 0;
  bool ended_after_action = false;
  EXPECT_EQ(entriesError(path, &entries, &ended_after_action), "");
  EXPECT_EQ(entries, 1u);
  EXPECT_TRUE(ended_after_action);
  EXPECT_EQ(gasp::readRawlogFrames(path).size(), 1u);
}

TEST(RawlogEntries, MrptsOwnSampleRawlogsThatEndAfterAnActionAreRead) {
  const std::string path = "/usr/share/mrpt/datasets/kf-slam_demo.rawlog";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is not installed (Debian package mrpt-common)";
  std::size_t entries = 0, objects = 0;
  bool ended_after_action = false;
  EXPECT_EQ(entriesError(path, &entries, &ended_after_action, &objects), "");
  // A sensory frame, 249 (action, sensory frame) pairs, and an action without its sensory frame.
  EXPECT_EQ(entries, 250u);
  EXPECT_TRUE(ended_after_action);
  EXPECT_EQ(objects, 500u);
  try {
    gasp::readRawlogFrames(path);
    FAIL() << "expected gasp::Error: the file holds no 3D scan";
  } catch (const gasp::Error& e) {
    EXPECT_TRUE(contains(e.what(), "no CObservation3DRangeScan")) << e.what();
  }
}

TEST(RawlogEntries, AnUnknownClassIsNamed) {
  // An odometry observation whose class name is changed to one no library registers (as a
  // rawlog written with a plugin's observation class, read without the plugin).
  const std::string path = gasp::test::scratchDir() + "/unknown.rawlog";
  {
    mrpt::io::CFileOutputStream out(path);  // plain, so that the class name can be edited
    auto ar = mrpt::serialization::archiveFrom(out);
    mrpt::obs::CObservationOdometry odo;
    ar << tinyScan() << odo;
  }
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const auto at = bytes.find("CObservationOdometry");
  ASSERT_NE(at, std::string::npos);
  bytes.replace(at, 20, "CObservationOdometrZ");
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;

  const std::string msg = entriesError(path);
  EXPECT_TRUE(contains(msg, "object #1") && contains(msg, "CObservationOdometrZ") &&
              contains(msg, "does not know"))
      << msg;
  gasp::RawlogReader reader(path);
  EXPECT_TRUE(reader.next().has_value());  // the scan before it
  try {
    reader.next();
    FAIL() << "expected gasp::Error for the unknown class";
  } catch (const gasp::Error& e) {
    EXPECT_TRUE(contains(e.what(), "CObservationOdometrZ")) << e.what();
  }
}

using gasp::test::fileText;

TEST(RawlogWriter, AFailedRunLeavesTheEarlierRawlogAsItWas) {
  const std::string dir = gasp::test::scratchDir();
  const std::string path = dir + "/kept.rawlog";
  {
    gasp::RawlogWriter writer(path);
    for (int i = 0; i < 2; ++i) writer.write(gasp::test::syntheticFrame(1.0 + i));
    EXPECT_FALSE(std::filesystem::exists(path)) << "published before close()";
    writer.close();
  }
  const std::string before = fileText(path);
  ASSERT_EQ(gasp::readRawlogFrames(path).size(), 2u);

  // An exception while writing: the partial file is removed, the earlier rawlog stays.
  try {
    gasp::RawlogWriter writer(path);
    writer.write(gasp::test::syntheticFrame(5.0));
    throw std::runtime_error("the run failed");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(fileText(path), before);
  EXPECT_FALSE(std::filesystem::exists(path + ".partial"));

  // discard() says the same without an exception.
  {
    gasp::RawlogWriter writer(path);
    writer.write(gasp::test::syntheticFrame(5.0));
    writer.discard();
    writer.close();  // no-op once discarded
  }
  EXPECT_EQ(fileText(path), before);
  EXPECT_FALSE(std::filesystem::exists(path + ".partial"));

  // A run that ends normally replaces it (the destructor closes).
  {
    gasp::RawlogWriter writer(path);
    for (int i = 0; i < 3; ++i) writer.write(gasp::test::syntheticFrame(7.0 + i));
  }
  EXPECT_EQ(gasp::readRawlogFrames(path).size(), 3u);
  // Nothing but the rawlog is left in its folder (no temporary file of any of the runs).
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  EXPECT_EQ(names, std::vector<std::string>{"kept.rawlog"});

  // A folder where the rawlog should be: a clear error.
  std::filesystem::create_directories(dir + "/folder.rawlog");
  try {
    gasp::RawlogWriter writer(dir + "/folder.rawlog");
    FAIL() << "expected gasp::Error";
  } catch (const gasp::Error& e) {
    EXPECT_TRUE(contains(e.what(), "is a folder")) << e.what();
  }
}

TEST(Tum2RawlogProgram, AFrameThatCannotBeReadLeavesTheEarlierOutputAsItWas) {
  // A TUM folder of three frames, the third not an image: the conversion fails (exit 1) and an
  // existing rawlog of the same name is neither replaced by a shorter one nor removed.
  const std::string dir = gasp::test::scratchDir();
  const std::string tum = dir + "/tum";
  std::filesystem::create_directories(tum + "/depth");
  std::ofstream list(tum + "/depth.txt");
  list << "# timestamp filename\n";
  for (int i = 0; i < 3; ++i) {
    const std::string name = "depth/" + std::to_string(i) + ".png";
    if (i < 2)
      ASSERT_TRUE(cv::imwrite(tum + "/" + name, gasp::test::syntheticFrame(1.0, 640, 480).depth_raw));
    else
      std::ofstream(tum + "/" + name) << "not a png";
    list << 10.0 + i << ' ' << name << '\n';
  }
  list.close();
  const std::string program = std::string(GASP_BIN_DIR) + "/gasp-tum2rawlog";
  const std::string out = dir + "/out.rawlog";
  std::ofstream(out) << "an earlier rawlog";
  const std::string cmd = "'" + program + "' '" + tum + "' '" + out + "' --intrinsics ros 2> '" + dir + "/stderr.txt'";
  EXPECT_EQ(WEXITSTATUS(std::system(cmd.c_str())), 1);
  EXPECT_TRUE(contains(fileText(dir + "/stderr.txt"), "2.png")) << fileText(dir + "/stderr.txt");
  EXPECT_EQ(fileText(out), "an earlier rawlog");
  EXPECT_FALSE(std::filesystem::exists(out + ".partial"));

  // Output onto the folder's own listing: refused before anything is written.
  const std::string onto = "'" + program + "' '" + tum + "' '" + tum + "/depth.txt' 2> '" + dir + "/stderr2.txt'";
  EXPECT_EQ(WEXITSTATUS(std::system(onto.c_str())), 1);
  EXPECT_TRUE(contains(fileText(dir + "/stderr2.txt"), "is an input of this run")) << fileText(dir + "/stderr2.txt");
  EXPECT_TRUE(contains(fileText(tum + "/depth.txt"), "depth/0.png"));
}

TEST(RawlogReader, ObservationClassesOfMrptMapsAreKnownToEveryReader) {
  // CObservationRotatingScan is registered by mrpt-maps, which a program that reads rawlogs need
  // not otherwise use (this test links gasp::rawlog alone): it is read and skipped by name.
  const std::string path = "/usr/share/mrpt/datasets/rot_scan_2d.rawlog";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is not installed (Debian package mrpt-common)";
  const std::string msg = readError(path);
  EXPECT_TRUE(contains(msg, "no CObservation3DRangeScan of depth in the file (it holds 1 x CObservationRotatingScan)")) << msg;
  EXPECT_FALSE(contains(msg, "does not know")) << msg;
}

// Crash inputs found by fuzz/fuzz_rawlog (docs/experiments/2026-11-28-fuzzing.md), kept in
// tests/rawlog/data: rawlogs of 32 x 24 frames with one corrupted size field, which MRPT allocated
// from before reading what follows (MRPT's serialisation has no length prefix). Before the size
// check (object_size_check.h) the range image of 480 x 16712320 pixels segfaulted (issue 44: a
// byte flipped at offset 171), the 1370953473 points ended in std::bad_alloc thrown through
// noexcept (abort), the sensory frame's count in a bad_alloc, the camera name in a 4 GB string, a
// sensor pose whose class name is garbled (MRPT reads it anyway) in a 92 GB range image, a
// sensory frame whose namespace is garbled (MRPT finds the class by its last part) in a 2 GB deque,
// likewise an action collection inside a sensory frame whose name has a zero byte after it, and a
// sensory frame of serialisation version 0 (an ID and a timestamp before its count), and a scan
// of serialisation version 0 (the points' count comes right after the pose), and a sensory frame
// as the second of a sensory frame's objects (every object inside is followed now, not the first),
// and a file cut inside an action collection's count (MRPT reads a partial field and goes on with
// the garbage: CArchive::ReadBuffer throws only when it reads nothing at all), and a CRawlog
// where an entry should be (MRPT deserialises any registered class; its object count asked for
// 27 GB): each object's class must be one a rawlog holds there.
// Each is now a gasp::Error naming the file, the object and the field, gzip-compressed or not.
TEST(RawlogErrors, CorruptSizeFieldsAreErrorsNamingTheObject) {
  const std::filesystem::path data = std::filesystem::path(__FILE__).parent_path() / "data";
  const struct {
    const char* file;
    const char* expected;
  } cases[] = {
      {"range_image_size_flipped.rawlog",
       "object #0 (at byte 0 of 13479): corrupt or truncated: CObservation3DRangeScan: range image of 480 x 16712320 pixels needs "
       "16043827200 bytes but 13306 bytes remain in the stream"},
      {"point_count_flipped.rawlog",
       "object #0 (at byte 0 of 13479): corrupt or truncated: CObservation3DRangeScan: 1370953473 3D points need 21935255568 bytes"},
      {"sensory_frame_count_flipped.rawlog",
       "object #1 (at byte 35 of 13677): corrupt or truncated: CSensoryFrame claims 4278190081 objects but 13612 bytes remain"},
      {"pose_class_name_flipped.rawlog",  // MRPT reads a nested CPose3D whatever its class name says
       "object #1 (at byte 35 of 5869): corrupt or truncated: CObservation3DRangeScan: range image of 24 x 1919759438 "
       "pixels needs 92148453024 bytes"},
      {"sensory_frame_namespace_garbled.rawlog",  // 'mrpt::ob@::CSensoryFrame': MRPT finds it by 'CSensoryFrame'
       "object #1 (at byte 35 of 188): corrupt or truncated: CSensoryFrame claims 2399141889 objects but 123 bytes "
       "remain"},
      {"action_collection_name_with_zero.rawlog",  // a zero byte ends the name MRPT looks up
       "object #1 (at byte 35 of 278): corrupt or truncated: a 'mrpt::obs::CActionCollection' where a rawlog holds an "
       "observation (inside a sensory frame)"},
      {"sensory_frame_version0_count.rawlog",  // version 0: an ID and a timestamp before the count
       "object #1 (at byte 35 of 118): corrupt or truncated: CSensoryFrame claims 976909154 objects but 41 bytes "
       "remain"},
      {"scan_version0_point_count.rawlog",  // a zero byte made the scan version 0 (no hasPoints3D flag)
       "object #0 (at byte 0 of 222): corrupt or truncated: CObservation3DRangeScan: 3071738112 3D points need "
       "39932595456 bytes but 59 bytes remain"},
      {"nested_sensory_frame_count.rawlog",  // the second object inside a sensory frame: a sensory frame
       "object #1 (at byte 35 of 406): corrupt or truncated: a 'mrpt::obs::CActionCollection' where a rawlog holds an "
       "observation (inside a sensory frame)"},
      {"action_collection_count_cut.rawlog",  // 33 bytes: the count's last byte missing
       "object #0 (at byte 0 of 33): corrupt or truncated: the stream ends inside this object (30 bytes of it read, "
       "33 bytes in the rest of the stream, a field needs more)"},
      {"intensity_flag_126.rawlog",  // a bool byte of 126: undefined behaviour where GASP reads the flag (UBSan)
       "object #3 (at byte 4594 of 13036): corrupt or truncated: CObservation3DRangeScan: hasIntensityImage is 126, "
       "not 0 or 1"},
      {"rawlog_class_as_entry.rawlog",  // 'mrpt::obsmrpt::obs::CRawlog': MRPT would read a CRawlog (27 GB)
       "object #0 (at byte 0 of 103): corrupt or truncated: a 'mrpt::obs::CRawlog' where a rawlog holds an "
       "observation, a sensory frame or an action collection"},
      {"camera_name_length_flipped.rawlog",
       "object #5 (at byte 4485 of 6675): corrupt or truncated: CObservation3DRangeScan: cameraParamsIntensity camera name claims "
       "4025563904 bytes but 165 bytes remain"},
      {"scan_version0_label_length.rawlog",  // fuzz_rawlog: a version 0 scan (MRPT 1) cut inside its label's length
       "object #1 (at byte 35 of 243): corrupt or truncated: the stream ends inside this object (205 bytes of it read, "
       "208 bytes in the rest of the stream, a field needs more)"},
  };
  const std::string dir = gasp::test::scratchDir();
  for (const auto& c : cases) {
    const std::string plain = (data / c.file).string();
    EXPECT_PRED2(contains, readError(plain), "rawlog '" + plain + "': " + c.expected) << c.file;
    // The same content gzip-compressed: its length comes from the zlib stream, not the file size.
    std::ifstream in(plain, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string gz = dir + "/" + c.file;
    {
      mrpt::io::CFileGZOutputStream out(gz);
      out.Write(bytes.data(), bytes.size());
    }
    EXPECT_PRED2(contains, readError(gz), "rawlog '" + gz + "': " + c.expected) << c.file << " (gzip)";
  }
  // A gzip stream damaged after 21204 bytes whose scans (a garbled TCamera, a 1.9 GB camera name)
  // MRPT read as far as zlib let it: the content's length is what inflate gives before the damage
  // (gzread dropped the whole last buffer, so the size check saw nothing left), the damage is the
  // error.
  const std::string damaged = (data / "gzip_damaged_camera_name.rawlog").string();
  EXPECT_PRED2(contains, readError(damaged), "rawlog '" + damaged + "': corrupt or truncated gzip stream: incorrect data check");
}

// fuzz_rawlog (a std::exception other than gasp::Error, which the harness logs): an externally
// stored range image whose file name has two characters made MRPT's lazy_load_absolute_path()
// assert; that MRPT exception left RawlogReader as it was. Now a gasp::Error naming the scan.
TEST(RawlogErrors, MrptErrorsOfAScanAreErrorsNamingTheScan) {
  const std::string dir = gasp::test::scratchDir();
  auto scan = tinyScan();
  scan.rangeImage_convertToExternalStorage("abc", dir + "/");
  std::string bytes;
  {
    mrpt::io::CMemoryStream mem;
    auto ar = mrpt::serialization::archiveFrom(mem);
    ar << scan;
    bytes.assign(static_cast<const char*>(mem.getRawBufferData()), mem.getTotalBytesCount());
  }
  // The stored name (MRPT may add an extension): uint32 length, then "abc...".
  const auto at = bytes.find("abc");
  ASSERT_TRUE(at != std::string::npos && at >= 4);
  const auto length = static_cast<std::size_t>(static_cast<unsigned char>(bytes[at - 4]));
  bytes.replace(at - 4, 4 + length, std::string("\x02\x00\x00\x00" "ab", 6));  // the file name "ab"
  const std::string path = dir + "/short_name.rawlog";
  std::ofstream(path, std::ios::binary) << bytes;
  const std::string msg = readError(path);
  EXPECT_TRUE(contains(msg, "rawlog '" + path + "', 3D scan #0: ")) << msg;
  EXPECT_TRUE(contains(msg, "fil.size() > 2")) << msg;  // MRPT's assertion, kept in the message
}

namespace {

/// A CObservation3DRangeScan of an older serialisation version (MRPT 1 wrote versions up to 8),
/// written field by field as MRPT 2.5's serializeFrom() reads that version: a 3 x 4 range image
/// at 1.5 m, a 4 x 3 grey intensity image, cameras, poses and matrices in the versions given.
struct OldScan {
  int version = 8;
  int pose_version = 2;
  int camera_version = 4;
  int image_version = 8;
};

class Bytes {
 public:
  template <class T>
  Bytes& operator<<(T value) {
    bytes_.append(reinterpret_cast<const char*>(&value), sizeof(T));
    return *this;
  }
  Bytes& header(const std::string& name, int version) {
    *this << static_cast<std::uint8_t>(0x80 | name.size());
    bytes_ += name;
    return *this << static_cast<std::uint8_t>(version);
  }
  Bytes& end() { return *this << std::uint8_t{0x88}; }
  Bytes& string(const std::string& s) {
    *this << static_cast<std::uint32_t>(s.size());
    bytes_ += s;
    return *this;
  }
  template <class T>
  Bytes& matrix(const char* name, std::uint32_t rows, std::uint32_t cols, T value) {
    header(name, 0) << rows << cols;
    for (std::uint32_t i = 0; i < rows * cols; ++i) *this << value;
    return end();
  }
  const std::string& str() const { return bytes_; }

 private:
  std::string bytes_;
};

void writePose(Bytes& b, int version) {
  b.header("CPose3D", version);
  if (version == 0) b.matrix<float>("CMatrixF", 4, 4, 0.f);
  if (version == 1) b.matrix<double>("CMatrixD", 4, 4, 0.0);
  if (version == 2) b << 0.0 << 0.0 << 0.0 << 1.0 << 0.0 << 0.0 << 0.0;  // x y z qr qx qy qz
  if (version == 3)
    for (double v : {0., 0., 0., 1., 0., 0., 0., 1., 0., 0., 0., 1.}) b << v;
  b.end();
}

void writeCamera(Bytes& b, int version) {
  b.header("TCamera", version) << 0.01;                             // focal length (m)
  for (int i = 0; i < (version >= 3 ? 8 : 5); ++i) b << 0.0;        // distortion
  if (version < 4) {
    b.header("CMatrixD", 0) << std::uint32_t{3} << std::uint32_t{3};
    for (double v : {5., 0., 1.5, 0., 5., 1., 0., 0., 1.}) b << v;  // fx 0 cx; 0 fy cy; 0 0 1
    b.end();
  } else {
    b << 5.0 << 5.0 << 1.5 << 1.0;  // fx fy cx cy
  }
  if (version == 0) b.matrix<double>("CMatrixD", 1, 5, 0.0);
  if (version >= 2) b << std::uint32_t{3} << std::uint32_t{4};  // nrows, ncols
  if (version >= 5) b.string("cam");
  if (version >= 6) b << std::uint8_t{0};
  b.end();
}

void writeGreyImage(Bytes& b, int version) {
  b.header("CImage", version);
  if (version == 0) {
    b << std::uint32_t{4} << std::uint32_t{3} << std::uint32_t{1} << std::uint8_t{0} << std::uint32_t{12};
  } else {
    if (version >= 6) b << std::uint8_t{0};  // not stored externally
    b << std::uint8_t{0};                    // grey
    b << std::int32_t{4} << std::int32_t{3} << std::int32_t{0} << std::int32_t{12};  // width height origin bytes
    if (version >= 9) b << std::int32_t{0};  // 8-bit depth
    if (version >= 5) b << std::uint8_t{0};  // not zipped
  }
  for (int i = 0; i < 12; ++i) b << std::uint8_t(i);
  b.end();
}

std::string oldScanBytes(const OldScan& s) {
  Bytes b;
  b.header("CObservation3DRangeScan", s.version) << 5.0f;  // maxRange
  writePose(b, s.pose_version);
  if (s.version > 0) b << std::uint8_t{1};  // hasPoints3D
  b << std::uint32_t{2};                    // two points
  for (float v : {0.f, 1.f, 0.f, 1.f, 1.5f, 1.5f}) b << v;  // x0 x1 y0 y1 z0 z1
  if (s.version == 0) b << std::uint8_t{1} << std::uint8_t{1};  // valid
  if (s.version >= 8) b << std::uint16_t{0} << std::uint16_t{1} << std::uint16_t{0} << std::uint16_t{0};
  if (s.version >= 1) {
    b << std::uint8_t{1};  // hasRangeImage
    if (s.version >= 9) b << 0.001f;
    if (s.version < 9) {
      b.matrix<float>("CMatrixF", 3, 4, 1.5f);
    } else {
      b << std::uint32_t{3} << std::uint32_t{4};
      for (int i = 0; i < 12; ++i) b << std::uint16_t{1500};
    }
    // The intensity image (TCamera before version 2 holds no size: MRPT takes 640 x 480).
    const bool intensity = s.camera_version >= 2;
    b << std::uint8_t{intensity};  // hasIntensityImage
    if (intensity) writeGreyImage(b, s.image_version);
    b << std::uint8_t{0};  // hasConfidenceImage
    if (s.version >= 2) writeCamera(b, s.camera_version);
    if (s.version >= 4) {
      writeCamera(b, s.camera_version);
      writePose(b, s.pose_version);
    }
  }
  b << 0.01f << std::uint64_t{0};  // stdError, timestamp
  b.string("old_scan");
  if (s.version >= 3) {  // the points and the range image not stored externally
    b << std::uint8_t{0};
    b.string("");
    b << std::uint8_t{0};
    b.string("");
  }
  if (s.version >= 5) b << std::uint8_t{1};  // range_is_depth
  if (s.version >= 6) b << std::int8_t{0};   // intensity channel
  if (s.version >= 7) b << std::uint8_t{0};  // no pixel labels
  if (s.version >= 10) b << std::uint8_t{0};
  b.end();
  return b.str();
}

}  // namespace

// fuzz_rawlog: a version 0 scan (MRPT 1) whose sensor label claimed 1.8 GB, which the size check
// did not follow past the 3D points. Every version MRPT reads is now followed to its end: scans of
// versions 0 to 10 with the poses, cameras, images and matrices of the versions MRPT reads are
// read by MRPT and pass the check, and a size in any of their fields that does not fit is an error.
TEST(RawlogErrors, ScansOfEveryVersionMrptReadsAreFollowedToTheirEnd) {
  const std::string dir = gasp::test::scratchDir();
  std::vector<OldScan> scans;
  for (int v = 0; v <= 10; ++v) scans.push_back({v, 2, 4, 8});
  for (int p = 0; p <= 3; ++p) scans.push_back({8, p, 4, 8});
  for (int c = 0; c <= 6; ++c) scans.push_back({8, 2, c, 8});
  for (int i : {0, 2, 4, 5, 6, 7, 9}) scans.push_back({8, 2, 4, i});  // 3: always zipped, which MRPT refuses
  for (const OldScan& s : scans) {
    const std::string label = "scan version " + std::to_string(s.version) + ", CPose3D " +
                              std::to_string(s.pose_version) + ", TCamera " + std::to_string(s.camera_version) +
                              ", CImage " + std::to_string(s.image_version);
    const std::string bytes = oldScanBytes(s);
    {  // MRPT reads it to its end (the layout written above is the one MRPT reads)
      mrpt::io::CMemoryStream mem;
      mem.assignMemoryNotOwn(bytes.data(), bytes.size());
      auto ar = mrpt::serialization::archiveFrom(mem);
      mrpt::serialization::CSerializable::Ptr obj;
      ASSERT_NO_THROW(obj = ar.ReadObject()) << label;
      EXPECT_EQ(mem.getPosition(), bytes.size()) << label;
      auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(obj);
      ASSERT_TRUE(scan) << label;
      EXPECT_EQ(scan->sensorLabel, "old_scan") << label;
      if (s.version >= 1 && s.camera_version >= 2) {
        EXPECT_EQ(scan->intensityImage.getWidth(), 4u) << label;
      }
    }
    const std::string path = dir + "/old_scan.rawlog";
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
    // The check lets it through and GASP reads the frame (version 0 has only 3D points, which a
    // reader of depth images leaves out as it leaves out a sweep; version 1 has no camera).
    if (s.version == 0) {
      EXPECT_PRED2(contains, readError(path), "it holds 1 x CObservation3DRangeScan of 3D points without a range image")
          << label;
    } else if (s.version == 1) {
      EXPECT_PRED2(contains, readError(path), "cameraParams: camera intrinsics: focal lengths must be positive") << label;
    } else {
      std::vector<gasp::RgbdFrame> frames;
      ASSERT_NO_THROW(frames = gasp::readRawlogFrames(path)) << label << ": " << readError(path);
      ASSERT_EQ(frames.size(), 1u) << label;
      EXPECT_FLOAT_EQ(frames[0].depth_m.at<float>(2, 3), 1.5f) << label;
    }
    // The sensor label's length (its 4 bytes before "old_scan") made 1.8 GB: an error naming it.
    std::string flipped = bytes;
    const auto at = flipped.find("old_scan");
    flipped[at - 1] = '\x6e';
    std::ofstream(path, std::ios::binary | std::ios::trunc) << flipped;
    EXPECT_PRED2(contains, readError(path), "CObservation3DRangeScan: sensorLabel claims 1845493768 bytes") << label;
  }
}
