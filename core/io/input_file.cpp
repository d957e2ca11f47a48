#include "io/input_file.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace hofem {

namespace {

// One cap: its command-line name, unit and a way to write it.
struct LimitField {
  const char* name;
  double unit;  // the cap holds value * unit
  void (*set)(InputLimits&, double);
};

constexpr double kMiB = 1024.0 * 1024.0;
const LimitField kFields[] = {
    {"mesh-file-mb", kMiB, [](InputLimits& l, double v) { l.mesh_file_bytes = static_cast<std::uint64_t>(v); }},
    {"scene-file-kb", 1024.0, [](InputLimits& l, double v) { l.scene_file_bytes = static_cast<std::uint64_t>(v); }},
    {"elements", 1.0, [](InputLimits& l, double v) { l.elements = static_cast<long long>(v); }},
    {"nodes", 1.0, [](InputLimits& l, double v) { l.nodes = static_cast<long long>(v); }},
    {"order", 1.0, [](InputLimits& l, double v) { l.order = static_cast<int>(v); }},
    {"json-depth", 1.0, [](InputLimits& l, double v) { l.json_depth = static_cast<int>(v); }},
    {"boundary-entries", 1.0, [](InputLimits& l, double v) { l.boundary_entries = static_cast<long long>(v); }},
};

const char* file_kind(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// Reads fd to its end, failing past max_bytes (the size of a regular file was
// checked before, but a file can grow while it is read; stdin has no size).
std::string read_all(int fd, const std::string& path, std::string_view what, std::uint64_t max_bytes) {
  std::string text;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n == 0) return text;
    if (n < 0) {
      if (errno == EINTR) continue;
      throw InputError(fmt::format("{}: cannot read {}: {}", path, what, std::strerror(errno)));
    }
    if (text.size() + static_cast<std::uint64_t>(n) > max_bytes)
      throw InputError(fmt::format("{}: {} is larger than the cap of {} bytes (raise it with --limit)", path, what,
                                   max_bytes));
    text.append(buffer, static_cast<std::size_t>(n));
  }
}

}  // namespace

InputLimits& input_limits() {
  static InputLimits limits;
  return limits;
}

std::vector<std::string> input_limit_names() {
  std::vector<std::string> names;
  for (const LimitField& f : kFields) names.emplace_back(f.name);
  return names;
}

void set_input_limit(std::string_view name_equals_value, InputLimits& limits) {
  const std::size_t eq = name_equals_value.find('=');
  const std::string_view name = name_equals_value.substr(0, eq);
  for (const LimitField& f : kFields) {
    if (name != f.name) continue;
    const std::string value(eq == std::string_view::npos ? std::string_view() : name_equals_value.substr(eq + 1));
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(value.c_str(), &end);
    // Whole positive numbers only, and small enough for the cap's integer type.
    if (value.empty() || *end != '\0' || errno == ERANGE || !(v >= 1.0) || v != std::floor(v) || v * f.unit > 9e18 ||
        ((std::string_view(f.name) == "json-depth" || std::string_view(f.name) == "order") && v > 100000))
      throw std::invalid_argument(fmt::format("--limit {}: '{}' is not a positive whole number in range", f.name, value));
    f.set(limits, v * f.unit);
    return;
  }
  throw std::invalid_argument(fmt::format("--limit: unknown cap '{}' (valid: {}; e.g. --limit elements=5e7)", name,
                                          fmt::join(input_limit_names(), ", ")));
}

std::string read_input_file(const std::string& path, std::string_view what, std::uint64_t max_bytes) {
  if (path == "-") return read_all(STDIN_FILENO, "<stdin>", what, max_bytes);
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    throw InputError(fmt::format("{}: cannot open {}: {}", path, what, std::strerror(errno)));
  if (!S_ISREG(st.st_mode))
    throw InputError(fmt::format("{}: cannot read {}: it is {}, not a regular file (use '-' to read stdin)", path, what,
                                 file_kind(st.st_mode)));
  if (static_cast<std::uint64_t>(st.st_size) > max_bytes)
    throw InputError(fmt::format("{}: {} is {} bytes, over the cap of {} bytes (raise it with --limit)", path, what,
                                 st.st_size, max_bytes));
  // O_NONBLOCK: should the path be swapped for a FIFO after the stat, open()
  // returns instead of waiting for a writer; fstat then refuses it.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw InputError(fmt::format("{}: cannot open {}: {}", path, what, std::strerror(errno)));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode))
    throw InputError(fmt::format("{}: cannot read {}: it is {}, not a regular file", path, what, file_kind(st.st_mode)));
  return read_all(fd, path, what, max_bytes);
}

std::string mesh_size_excess(long long elements, long long nodes) {
  const InputLimits& l = input_limits();
  if (elements > l.elements)
    return fmt::format("{} elements exceed the cap of {} (raise it with --limit elements=N)", elements, l.elements);
  if (nodes > l.nodes)
    return fmt::format("{} nodes exceed the cap of {} (raise it with --limit nodes=N)", nodes, l.nodes);
  return {};
}

}  // namespace hofem
