#include "provenance/provenance.hpp"

#include "provenance/build_commit.hpp"

#include <omp.h>
#include <unistd.h>

#include <ctime>
#include <fstream>
#include <thread>

namespace hofem {

namespace {

// The model name of the first processor in /proc/cpuinfo ("unknown" elsewhere).
std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0)
      if (const auto colon = line.find(':'); colon != std::string::npos)
        return line.substr(line.find_first_not_of(" \t", colon + 1));
  return "unknown";
}

std::string hostname() {
  char name[256] = {};
  return gethostname(name, sizeof name - 1) == 0 ? name : "unknown";
}

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

}  // namespace

std::string_view hofem_version() { return HOFEM_VERSION; }

std::string version_text() {
  std::string text = "hofem " HOFEM_VERSION " (commit ";
  text += detail::build_commit();
  if (detail::build_dirty()) text += "-dirty";
  text += ", " HOFEM_BUILD_TYPE " build, " HOFEM_COMPILER ")";
  return text;
}

nlohmann::json provenance_context(std::string_view preset) {
  return {{"schema_version", kOutputSchemaVersion},
          {"hofem_version", HOFEM_VERSION},
          {"commit", detail::build_commit()},
          {"dirty", detail::build_dirty()},
          {"date", utc_now()},
          {"build_type", HOFEM_BUILD_TYPE},
          {"compiler", HOFEM_COMPILER},
          {"flags", HOFEM_COMPILE_FLAGS},
          {"preset", preset},
          {"hostname", hostname()},
          {"cpu", cpu_model()},
          {"cores", std::thread::hardware_concurrency()},
          {"threads", omp_get_max_threads()}};
}

}  // namespace hofem
