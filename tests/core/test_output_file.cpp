// gasp::OutputFile: an output appears whole or not at all, never replaces anything but a regular
// file, and reports every failed write (a full disk, a file-size limit) naming the file.
#include <gtest/gtest.h>
#include <sched.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "gasp/core/error.h"
#include "gasp/core/output_file.h"
#include "gasp_test_data.h"

namespace fs = std::filesystem;

namespace {

using gasp::test::fileText;
using gasp::test::namesIn;

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

/// The gasp::Error message of `f`, or "" when it throws none.
template <class F>
std::string errorOf(F&& f) {
  try {
    f();
  } catch (const gasp::Error& e) {
    return e.what();
  }
  return "";
}

/// Runs `f` in a child process and returns its exit code (for faults a test must not inflict on
/// itself: a file-size limit, a kill).
template <class F>
int inChild(F&& f) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    int code = 99;
    try {
      code = f();
    } catch (...) {
      code = 98;
    }
    ::_exit(code);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace

TEST(OutputFile, AppearsWholeOnCommitAndLeavesNothingElse) {
  const std::string dir = gasp::test::scratchDir();
  const std::string path = dir + "/out.txt";
  {
    gasp::OutputFile out(path, "table");
    out.stream() << "line 1\n";
    out.write("line 2\n");
    EXPECT_FALSE(fs::exists(path)) << "published before commit()";
    out.commit();
    EXPECT_TRUE(out.committed());
    out.commit();  // a second call does nothing
  }
  EXPECT_EQ(fileText(path), "line 1\nline 2\n");
  EXPECT_EQ(namesIn(dir), std::vector<std::string>{"out.txt"});
}

TEST(OutputFile, WithoutCommitTheEarlierFileStaysAsItWas) {
  const std::string dir = gasp::test::scratchDir();
  const std::string path = dir + "/kept.txt";
  std::ofstream(path) << "earlier";
  {
    gasp::OutputFile out(path);
    out.stream() << std::string(200000, 'x');  // more than the stream's buffer
  }
  EXPECT_EQ(fileText(path), "earlier");
  {
    gasp::OutputFile out(path);
    out.stream() << "new";
    out.discard();
    EXPECT_FALSE(errorOf([&] { out.commit(); }).empty()) << "commit after discard";
  }
  EXPECT_EQ(fileText(path), "earlier");
  EXPECT_EQ(namesIn(dir), std::vector<std::string>{"kept.txt"});
}

TEST(OutputFile, RefusesWhatIsNotARegularFileBeforeAnyWrite) {
  const std::string dir = gasp::test::scratchDir();
  const std::string device = errorOf([] { gasp::OutputFile out("/dev/full", "--out"); });
  EXPECT_TRUE(contains(device, "cannot write --out '/dev/full'")) << device;
  EXPECT_TRUE(contains(device, "not a regular file")) << device;

  const std::string fifo = dir + "/fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_TRUE(contains(errorOf([&] { gasp::OutputFile out(fifo); }), "not a regular file"));

  fs::create_directories(dir + "/folder");
  EXPECT_TRUE(contains(errorOf([&] { gasp::OutputFile out(dir + "/folder"); }), "is a folder"));
  EXPECT_TRUE(contains(errorOf([&] { gasp::OutputFile out(dir + "/folder/"); }), "is a folder"));
  EXPECT_TRUE(contains(errorOf([&] { gasp::OutputFile out(dir + "/missing/x.txt"); }), "does not exist"));
  EXPECT_TRUE(contains(errorOf([] { gasp::OutputFile out(""); }), "no file name"));
  // A link to a device is as much a device.
  fs::create_symlink("/dev/null", dir + "/null_link");
  EXPECT_TRUE(contains(errorOf([&] { gasp::OutputFile out(dir + "/null_link"); }), "not a regular file"));
  EXPECT_TRUE(fs::is_symlink(dir + "/null_link"));
}

TEST(OutputFile, ASymbolicLinkStaysAndTheFileItNamesIsReplaced) {
  const std::string dir = gasp::test::scratchDir();
  fs::create_directories(dir + "/real");
  std::ofstream(dir + "/real/data.txt") << "old";
  fs::create_symlink("real/data.txt", dir + "/link.txt");
  gasp::OutputFile out(dir + "/link.txt");
  EXPECT_EQ(out.target(), fs::canonical(dir + "/real").string() + "/data.txt");
  out.stream() << "new";
  out.commit();
  EXPECT_TRUE(fs::is_symlink(dir + "/link.txt"));
  EXPECT_EQ(fileText(dir + "/real/data.txt"), "new");
  // A dangling link: the file it names is created.
  fs::create_symlink("real/created.txt", dir + "/dangling.txt");
  gasp::writeWholeFile(dir + "/dangling.txt", "made");
  EXPECT_TRUE(fs::is_symlink(dir + "/dangling.txt"));
  EXPECT_EQ(fileText(dir + "/real/created.txt"), "made");
}

TEST(OutputFile, KeepsTheReplacedFilesPermissions) {
  const std::string dir = gasp::test::scratchDir();
  const std::string path = dir + "/script.sh";
  std::ofstream(path) << "old";
  fs::permissions(path, fs::perms::owner_all | fs::perms::group_read);
  gasp::writeWholeFile(path, "new");
  EXPECT_EQ(fs::status(path).permissions() & fs::perms::all, fs::perms::owner_all | fs::perms::group_read);
}

TEST(OutputFile, AFailedWriteIsAnErrorAndTheTargetIsUntouched) {
  // A file-size limit makes write(2) fail with EFBIG as a full disk fails with ENOSPC; the child
  // ignores SIGXFSZ so that it sees the error instead of dying.
  const std::string dir = gasp::test::scratchDir();
  const std::string path = dir + "/big.txt";
  std::ofstream(path) << "earlier";
  const std::string message_file = dir + "/message.txt";
  const int code = inChild([&] {
    std::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{4096, 4096};
    if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) return 97;
    const std::string message = errorOf([&] {
      gasp::OutputFile out(path, "trajectory");
      for (int i = 0; i < 1000; ++i) out.stream() << "a line of a trajectory that will not fit\n";
      out.commit();
    });
    const rlimit unlimited{RLIM_INFINITY, RLIM_INFINITY};
    ::setrlimit(RLIMIT_FSIZE, &unlimited);
    std::ofstream(message_file) << message;
    return message.empty() ? 1 : 0;
  });
  ASSERT_EQ(code, 0) << "the write past the limit was not reported";
  const std::string message = fileText(message_file);
  EXPECT_TRUE(contains(message, "cannot write trajectory '" + path + "'")) << message;
  EXPECT_TRUE(contains(message, "File too large")) << message;
  EXPECT_EQ(fileText(path), "earlier");
  EXPECT_EQ(namesIn(dir), (std::vector<std::string>{"big.txt", "message.txt"}));
}

TEST(OutputFile, AKilledWriterLeavesNothingBehind) {
  const std::string dir = gasp::test::scratchDir();
  const std::string path = dir + "/out.txt";
  std::ofstream(path) << "earlier";
  const int code = inChild([&] {
    gasp::OutputFile out(path);
    out.stream() << std::string(1 << 20, 'x');
    out.stream().flush();
    ::raise(SIGKILL);  // no destructor, no handler runs
    return 0;
  });
  EXPECT_EQ(code, 128 + SIGKILL);
  EXPECT_EQ(fileText(path), "earlier");
  EXPECT_EQ(namesIn(dir), std::vector<std::string>{"out.txt"}) << "a temporary file was left";
}

TEST(OutputFile, AFullFileSystemIsAnError) {
  // A 64 KiB tmpfs in a private mount namespace, where the machine permits it (root, unshare).
  const std::string dir = gasp::test::scratchDir();
  const std::string mount = dir + "/small";
  fs::create_directories(mount);
  const std::string message_file = dir + "/message.txt";
  const int code = inChild([&] {
    if (::unshare(CLONE_NEWNS) != 0) return 77;
    if (std::system(("mount --make-rprivate / 2>/dev/null; mount -t tmpfs -o size=64k tmpfs '" + mount + "' 2>/dev/null")
                        .c_str()) != 0)
      return 77;
    std::ofstream(mount + "/kept.txt") << "earlier";
    const std::string message = errorOf([&] {
      gasp::OutputFile out(mount + "/kept.txt", "point cloud");
      for (int i = 0; i < 20000; ++i) out.stream() << "0.123456789 0.123456789 0.123456789\n";
      out.commit();
    });
    std::ofstream(message_file) << message;
    if (fileText(mount + "/kept.txt") != "earlier") return 2;
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(mount)) names.push_back(e.path().filename().string());
    if (names != std::vector<std::string>{"kept.txt"}) return 3;
    return message.empty() ? 1 : 0;
  });
  if (code == 77) GTEST_SKIP() << "no private tmpfs here (needs root and unshare); the file-size limit test covers the write error";
  EXPECT_EQ(code, 0) << "1: no error, 2: the earlier file changed, 3: a file was left";
  const std::string message = fileText(message_file);
  EXPECT_TRUE(contains(message, "cannot write point cloud")) << message;
  EXPECT_TRUE(contains(message, "No space left on device")) << message;
}

TEST(OutputFile, FileIdentitySeesThroughLinks) {
  const std::string dir = gasp::test::scratchDir();
  std::ofstream(dir + "/a.txt") << "a";
  fs::create_hard_link(dir + "/a.txt", dir + "/hard.txt");
  fs::create_symlink("a.txt", dir + "/soft.txt");
  EXPECT_TRUE(gasp::fileIdentity(dir + "/a.txt").exists());
  EXPECT_EQ(gasp::fileIdentity(dir + "/a.txt"), gasp::fileIdentity(dir + "/hard.txt"));
  EXPECT_EQ(gasp::fileIdentity(dir + "/a.txt"), gasp::fileIdentity(dir + "/soft.txt"));
  EXPECT_FALSE(gasp::fileIdentity(dir + "/none.txt").exists());
}

TEST(ErrorMessages, ArePrintableOneLiners) {
  EXPECT_EQ(gasp::printable("plain text"), "plain text");
  EXPECT_EQ(gasp::printable("caf\xc3\xa9 \xe2\x82\xac"), "caf\xc3\xa9 \xe2\x82\xac");  // valid UTF-8 kept
  EXPECT_EQ(gasp::printable(std::string("a\nb\x01\x7f", 5)), "a\\x0ab\\x01\\x7f");
  EXPECT_EQ(gasp::printable("\xff\xc3("), "\\xff\\xc3(");  // not UTF-8
  EXPECT_EQ(gasp::printable("\xc0\xaf"), "\\xc0\\xaf");    // an overlong form
  const gasp::Error e(std::string("bad line 'x\x1b[2Jy'"));
  EXPECT_EQ(gasp::exceptionMessage(e), "bad line 'x\\x1b[2Jy'");
}
