#include "io/state_file.hpp"

#include "io/atomic_file.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <bit>
#include <cmath>
#include <fstream>
#include <stdexcept>

namespace hofem {

static_assert(std::endian::native == std::endian::little, "state files hold little-endian doubles");

void write_state(const std::string& path, const StoredState& s) {
  if (s.x.size() != s.v.size() || !s.x.allFinite() || !s.v.allFinite() || !std::isfinite(s.t))
    throw std::invalid_argument(fmt::format("{}: a state needs finite t and equally many finite positions and velocities", path));
  const nlohmann::json header = {{"format", "hofem-state"}, {"version", 1}, {"t", s.t}, {"step", s.step},
                                 {"values", s.x.size()},    {"key", s.key}};
  AtomicFile file(path);
  file.write(header.dump() + "\n");
  const auto bytes = [](const Eigen::VectorXd& a) {
    return std::string_view(reinterpret_cast<const char*>(a.data()), sizeof(double) * static_cast<size_t>(a.size()));
  };
  file.write(bytes(s.x));
  file.write(bytes(s.v));
  file.commit();
}

StoredState read_state(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot open the state file", path));
  std::string line;
  if (!std::getline(in, line) || line.size() > 100000)
    throw std::runtime_error(fmt::format("{}: not a hofem state file (no header line)", path));
  nlohmann::json h;
  try {
    h = nlohmann::json::parse(line);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(fmt::format("{}: not a hofem state file (header: {})", path, e.what()));
  }
  StoredState s;
  try {
    if (h.at("format") != "hofem-state" || h.at("version") != 1)
      throw std::runtime_error(fmt::format("{}: not a version-1 hofem state file", path));
    s.key = h.at("key").get<std::string>();
    s.t = h.at("t").get<double>();
    s.step = h.at("step").get<int>();
    const long long n = h.at("values").get<long long>();
    if (n < 0 || n > (1ll << 34)) throw std::runtime_error(fmt::format("{}: header says {} values", path, n));
    s.x.resize(n);
    s.v.resize(n);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(fmt::format("{}: state header: {}", path, e.what()));
  }
  const auto read = [&](Eigen::VectorXd& a, const char* what) {
    in.read(reinterpret_cast<char*>(a.data()), static_cast<std::streamsize>(sizeof(double) * a.size()));
    if (in.gcount() != static_cast<std::streamsize>(sizeof(double) * a.size()))
      throw std::runtime_error(fmt::format("{}: truncated: the {} end early", path, what));
    if (!a.allFinite()) throw std::runtime_error(fmt::format("{}: non-finite {}", path, what));
  };
  read(s.x, "positions");
  read(s.v, "velocities");
  if (in.peek() != std::ifstream::traits_type::eof())
    throw std::runtime_error(fmt::format("{}: bytes after the velocities (not {} values each)", path, s.x.size()));
  if (!std::isfinite(s.t)) throw std::runtime_error(fmt::format("{}: non-finite time", path));
  return s;
}

}  // namespace hofem
