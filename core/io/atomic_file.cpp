#include "io/atomic_file.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <stdexcept>
#include <unistd.h>

namespace hofem {

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  temp_ = fmt::format("{}.partial-{}", path_, ::getpid());
  fd_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) fail("cannot create");
  const char* hook = std::getenv("HOFEM_TEST_KILL_WRITING");
  kill_midway_ = hook && *hook && std::filesystem::path(path_).filename() == hook;
}

AtomicFile::~AtomicFile() {
  if (fd_ < 0) return;
  ::close(fd_);
  ::unlink(temp_.c_str());
}

void AtomicFile::fail(const char* what) const {
  throw std::runtime_error(fmt::format("{} '{}': {}", what, path_, std::strerror(errno)));
}

void AtomicFile::write(std::string_view bytes) {
  if (kill_midway_) {
    // Half the bytes reach the temporary file, then the process dies as a
    // SIGKILL from outside would kill it.
    const std::string_view half = bytes.substr(0, bytes.size() / 2);
    [[maybe_unused]] const ssize_t n = ::write(fd_, half.data(), half.size());
    std::raise(SIGKILL);
  }
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd_, bytes.data(), bytes.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      fail("cannot write");
    }
    bytes.remove_prefix(static_cast<std::size_t>(n));
  }
}

void AtomicFile::commit() {
  // fsync before rename: otherwise a crash of the machine (not only of the
  // process) can leave the new name pointing at an empty file.
  if (::fsync(fd_) != 0 && errno != EINVAL) fail("cannot flush");
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) {
    ::unlink(temp_.c_str());
    fail("cannot write");
  }
  if (std::rename(temp_.c_str(), path_.c_str()) != 0) {
    ::unlink(temp_.c_str());
    fail("cannot rename the finished file to");
  }
}

void write_file_atomically(const std::string& path, std::string_view content) {
  AtomicFile file(path);
  file.write(content);
  file.commit();
}

}  // namespace hofem
