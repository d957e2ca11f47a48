#pragma once
// Output files that are either complete or absent: the bytes go to
// "<path>.partial-<pid>" in the same directory, which is flushed to disk and
// renamed over <path> only when everything is written (rename is atomic within
// a file system). A run killed mid-write - SIGKILL, a full disk, an exception -
// leaves at most a ".partial-" file, never a truncated file under the real name
// that a reader would take for a finished one; an older complete file stays.
//
// Test hook: when the environment variable HOFEM_TEST_KILL_WRITING names a
// file's base name, the process sends itself SIGKILL halfway through the first
// write to that file (the atomic-write test kills a run exactly there).
#include <string>
#include <string_view>

namespace hofem {

class AtomicFile {
 public:
  /// Creates the temporary file; throws std::runtime_error naming path.
  explicit AtomicFile(std::string path);
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  /// Without commit(): the temporary file is removed, <path> is untouched.
  ~AtomicFile();

  void write(std::string_view bytes);
  /// Flushes to disk and renames the temporary file to <path>.
  void commit();
  const std::string& path() const { return path_; }

 private:
  [[noreturn]] void fail(const char* what) const;
  std::string path_, temp_;
  int fd_ = -1;
  bool kill_midway_ = false;  // the test hook
};

/// Writes `content` to `path` through an AtomicFile.
void write_file_atomically(const std::string& path, std::string_view content);

}  // namespace hofem
