#pragma once
/// \file output_file.h An output file that appears whole or not at all, and never replaces
/// anything but a regular file.
///
/// Every file GASP writes goes through OutputFile: the bytes go to a temporary file in the
/// target's own folder (an unnamed O_TMPFILE where the file system has them, so that even a killed
/// run leaves nothing behind; else a hidden ".NAME.XXXXXX" file removed on failure), every write
/// is checked, and commit() flushes, fsyncs and renames it over the target in one step. A target
/// reached through symbolic links is resolved first, so the link stays and the file it names is
/// replaced; a target that exists and is not a regular file (a device such as /dev/full, a FIFO, a
/// socket, a folder) is refused when the OutputFile is opened, before any work.
#include <sys/types.h>

#include <memory>
#include <ostream>
#include <string>
#include <string_view>

namespace gasp {

class OutputFile {
 public:
  /// Opens the output now (so that a path that cannot be written fails before the work).
  /// `what` names the output in errors: "cannot write trajectory 'x.txt': No space left on
  /// device". Throws gasp::Error naming the path: a folder or a non-regular file, a folder that
  /// does not exist or cannot be written, an existing file without write permission.
  explicit OutputFile(const std::string& path, const std::string& what = "output file");
  /// Without commit(): the temporary file is removed and the target is left as it was.
  ~OutputFile();
  OutputFile(OutputFile&&) noexcept;
  OutputFile& operator=(OutputFile&&) noexcept;
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  /// The stream to write into (binary: no newline translation). A failed write sets its badbit
  /// and is reported by commit().
  std::ostream& stream();
  /// Appends raw bytes to the stream.
  void write(std::string_view bytes);
  /// A file descriptor of the temporary file, for writers that need one (zlib's gzdopen: dup()
  /// it first). Bytes written through it and through stream() must not interleave unflushed:
  /// use one or the other.
  int descriptor() const;

  /// Flushes, checks that every write succeeded, fsyncs the file, renames it over the target and
  /// fsyncs the folder. Throws gasp::Error naming the path and the system's reason (the target is
  /// then untouched). A second call does nothing.
  void commit();
  /// Drops what was written; the target is untouched. commit() is then an error.
  void discard();

  /// The path as given.
  const std::string& path() const;
  /// The file that commit() replaces: `path` with symbolic links resolved.
  const std::string& target() const;
  bool committed() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Identity of an existing file (device and inode, symbolic links followed), for "is this output
/// one of the inputs" checks that also see hard links; {0, 0} when the path does not exist.
struct FileIdentity {
  dev_t device = 0;
  ino_t inode = 0;
  bool exists() const { return device != 0 || inode != 0; }
  bool operator==(const FileIdentity& o) const { return device == o.device && inode == o.inode; }
  bool operator<(const FileIdentity& o) const { return device != o.device ? device < o.device : inode < o.inode; }
};
FileIdentity fileIdentity(const std::string& path);

/// Writes `bytes` to `path` through an OutputFile (whole or not at all).
void writeWholeFile(const std::string& path, std::string_view bytes, const std::string& what = "output file");

}  // namespace gasp
