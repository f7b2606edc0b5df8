#include "gasp/core/output_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <random>
#include <streambuf>

#include "gasp/core/error.h"

namespace gasp {

namespace {

namespace fs = std::filesystem;

std::string systemReason(int error) { return std::strerror(error); }

/// A stream buffer over a file descriptor that remembers the first failed write(2).
class DescriptorBuffer : public std::streambuf {
 public:
  explicit DescriptorBuffer(int fd) : fd_(fd) { setp(buffer_, buffer_ + sizeof buffer_); }
  int error() const { return error_; }
  bool flushAll() { return drain(); }

 protected:
  int_type overflow(int_type c) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override { return drain() ? 0 : -1; }

 private:
  bool drain() {
    if (error_ != 0) return false;
    const char* p = pbase();
    auto left = static_cast<std::size_t>(pptr() - pbase());
    while (left > 0) {
      const ssize_t n = ::write(fd_, p, left);
      if (n < 0) {
        if (errno == EINTR) continue;
        error_ = errno;
        return false;
      }
      p += n;
      left -= static_cast<std::size_t>(n);
    }
    setp(buffer_, buffer_ + sizeof buffer_);
    return true;
  }

  int fd_;
  int error_ = 0;
  char buffer_[1 << 16];
};

/// `path` with every symbolic link of its last component followed (a dangling link gives the
/// file it would create) and its folder made canonical.
fs::path resolveTarget(const std::string& path, const std::string& what) {
  std::error_code ec;
  fs::path p = fs::absolute(path, ec);
  if (ec) throw Error("cannot write " + what + " '" + path + "': " + ec.message());
  for (int hops = 0;; ++hops) {
    struct stat st {};
    if (::lstat(p.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) break;
    if (hops == 40) throw Error("cannot write " + what + " '" + path + "': too many levels of symbolic links");
    const fs::path link = fs::read_symlink(p, ec);
    if (ec) throw Error("cannot write " + what + " '" + path + "': " + ec.message());
    p = link.is_absolute() ? link : p.parent_path() / link;
  }
  const fs::path folder = fs::weakly_canonical(p.parent_path(), ec);
  return (ec ? p.parent_path() : folder) / p.filename();
}

std::string randomSuffix() {
  static std::atomic<unsigned> counter{0};
  static thread_local std::mt19937_64 rng{std::random_device{}() ^ static_cast<std::uint64_t>(::getpid())};
  const std::uint64_t v = rng() ^ (static_cast<std::uint64_t>(counter++) << 40);
  static const char digits[] = "abcdefghijklmnopqrstuvwxyz0123456789";
  std::string s(10, 'x');
  std::uint64_t x = v;
  for (char& c : s) {
    c = digits[x % 36];
    x /= 36;
  }
  return s;
}

/// The hidden name of a temporary file beside `target`.
fs::path temporaryName(const fs::path& target) {
  return target.parent_path() / ("." + target.filename().string() + "." + randomSuffix() + ".tmp");
}

void syncFolder(const fs::path& folder) {
  const int dfd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd < 0) return;
  static_cast<void>(::fsync(dfd));  // best effort: some file systems refuse fsync on a folder
  ::close(dfd);
}

}  // namespace

struct OutputFile::Impl {
  std::string path;
  std::string what;
  fs::path target;
  fs::path named_temporary;  ///< empty for an unnamed (O_TMPFILE) file
  int fd = -1;
  bool target_existed = false;
  mode_t target_mode = 0;
  bool committed = false;
  bool discarded = false;
  std::unique_ptr<DescriptorBuffer> buffer;
  std::unique_ptr<std::ostream> stream;

  std::string failure(const std::string& reason) const { return "cannot write " + what + " '" + path + "': " + reason; }

  void closeAndRemove() {
    if (fd >= 0) ::close(fd);
    fd = -1;
    if (!named_temporary.empty()) ::unlink(named_temporary.c_str());
    named_temporary.clear();
  }
};

OutputFile::OutputFile(const std::string& path, const std::string& what) : impl_(std::make_unique<Impl>()) {
  Impl& o = *impl_;
  o.path = path;
  o.what = what;
  if (path.empty()) throw Error("cannot write " + what + ": no file name given");
  o.target = resolveTarget(path, what);
  if (o.target.filename().empty() || o.target.filename() == "." || o.target.filename() == "..")
    throw Error(o.failure("is a folder, not a file"));

  struct stat st {};
  if (::stat(o.target.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) throw Error(o.failure("is a folder, not a file"));
    if (!S_ISREG(st.st_mode))
      throw Error(o.failure("is not a regular file (a device, FIFO or socket); outputs are written to regular files only"));
    if (::access(o.target.c_str(), W_OK) != 0) throw Error(o.failure("the file exists and cannot be overwritten"));
    o.target_existed = true;
    o.target_mode = st.st_mode & 07777;
  }
  const fs::path folder = o.target.parent_path();
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) throw Error(o.failure("the folder '" + folder.string() + "' does not exist"));
  if (::access(folder.c_str(), W_OK | X_OK) != 0) throw Error(o.failure("the folder '" + folder.string() + "' cannot be written"));

  // An unnamed file first: nothing is left behind whatever ends the run. Its publication needs
  // /proc/self/fd (linkat); without it, or where the file system has no O_TMPFILE, a named one.
#ifdef O_TMPFILE
  if (::access("/proc/self/fd", X_OK) == 0) o.fd = ::open(folder.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
#endif
  int last_error = 0;
  for (int attempt = 0; o.fd < 0 && attempt < 100; ++attempt) {
    const fs::path name = temporaryName(o.target);
    o.fd = ::open(name.c_str(), O_CREAT | O_EXCL | O_WRONLY | O_CLOEXEC, 0666);
    if (o.fd >= 0) {
      o.named_temporary = name;
    } else {
      last_error = errno;
      if (last_error != EEXIST) break;
    }
  }
  if (o.fd < 0)
    throw Error(o.failure("cannot create a file in the folder '" + folder.string() + "': " + systemReason(last_error)));
  o.buffer = std::make_unique<DescriptorBuffer>(o.fd);
  o.stream = std::make_unique<std::ostream>(o.buffer.get());
}

OutputFile::~OutputFile() {
  if (impl_ && !impl_->committed) impl_->closeAndRemove();
}
OutputFile::OutputFile(OutputFile&&) noexcept = default;
OutputFile& OutputFile::operator=(OutputFile&& other) noexcept {
  if (this != &other) {
    if (impl_ && !impl_->committed) impl_->closeAndRemove();
    impl_ = std::move(other.impl_);
  }
  return *this;
}

std::ostream& OutputFile::stream() { return *impl_->stream; }

void OutputFile::write(std::string_view bytes) { impl_->stream->write(bytes.data(), static_cast<std::streamsize>(bytes.size())); }

int OutputFile::descriptor() const { return impl_->fd; }

const std::string& OutputFile::path() const { return impl_->path; }
const std::string& OutputFile::target() const { return impl_->target.native(); }
bool OutputFile::committed() const { return impl_->committed; }

void OutputFile::discard() {
  if (impl_->committed) return;
  impl_->closeAndRemove();
  impl_->discarded = true;
}

void OutputFile::commit() {
  Impl& o = *impl_;
  if (o.committed) return;
  if (o.discarded) throw Error(o.failure("the output was discarded"));
  const auto fail = [&o](const std::string& reason) {
    o.closeAndRemove();
    o.discarded = true;
    throw Error(o.failure(reason));
  };
  o.buffer->flushAll();
  if (o.buffer->error() != 0) fail(systemReason(o.buffer->error()));
  if (!*o.stream) fail("the stream failed");
  if (::fsync(o.fd) != 0) fail(systemReason(errno));
  if (o.target_existed) static_cast<void>(::fchmod(o.fd, o.target_mode));  // keep the replaced file's permissions

  if (o.named_temporary.empty()) {
    // Give the unnamed file a hidden name beside the target, then rename it over the target.
    const std::string proc = "/proc/self/fd/" + std::to_string(o.fd);
    for (int attempt = 0; attempt < 100 && o.named_temporary.empty(); ++attempt) {
      const fs::path name = temporaryName(o.target);
      if (::linkat(AT_FDCWD, proc.c_str(), AT_FDCWD, name.c_str(), AT_SYMLINK_FOLLOW) == 0)
        o.named_temporary = name;
      else if (errno != EEXIST)
        fail("cannot name the finished file in its folder: " + systemReason(errno));
    }
    if (o.named_temporary.empty()) fail("cannot name the finished file in its folder");
  }
  const int fd = o.fd;
  o.fd = -1;
  if (::close(fd) != 0) fail(systemReason(errno));
  if (::rename(o.named_temporary.c_str(), o.target.c_str()) != 0) fail(systemReason(errno));
  o.named_temporary.clear();
  o.committed = true;
  syncFolder(o.target.parent_path());
}

FileIdentity fileIdentity(const std::string& path) {
  struct stat st {};
  if (path.empty() || ::stat(path.c_str(), &st) != 0) return {};
  return {st.st_dev, st.st_ino};
}

void writeWholeFile(const std::string& path, std::string_view bytes, const std::string& what) {
  OutputFile out(path, what);
  out.write(bytes);
  out.commit();
}

}  // namespace gasp
