#include "scene/run_checkpoint.hpp"

#include "io/atomic_file.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>

namespace hofem {

namespace fs = std::filesystem;

namespace {
constexpr const char* kRecord = "checkpoint.json";
std::string state_name(int step) { return fmt::format("state-{:08d}.state", step); }
}  // namespace

void write_checkpoint(const std::string& dir, const RunCheckpoint& c) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw std::runtime_error(fmt::format("{}: cannot create the checkpoint directory: {}", dir, ec.message()));
  const std::string name = state_name(c.state.step);
  StoredState s = c.state;
  s.key = c.key;
  write_state((fs::path(dir) / name).string(), s);
  const nlohmann::json record = {{"format", "hofem-checkpoint"}, {"version", 1}, {"key", c.key},
                                 {"step", c.state.step},         {"t", c.state.t}, {"state", name},
                                 {"record", c.record}};
  write_file_atomically((fs::path(dir) / kRecord).string(), record.dump() + "\n");
  // Only now may the older states go: the record no longer names them.
  static const std::regex kState(R"(state-\d+\.state)");
  for (const auto& entry : fs::directory_iterator(dir, ec))
    if (entry.path().filename() != name && std::regex_match(entry.path().filename().string(), kState))
      fs::remove(entry.path(), ec);
}

std::optional<RunCheckpoint> read_checkpoint(const std::string& dir, const std::string& key) {
  const fs::path path = fs::path(dir) / kRecord;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return std::nullopt;
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text.str());
  } catch (const std::exception& e) {
    throw std::runtime_error(fmt::format("{}: not a checkpoint record: {}", path.string(), e.what()));
  }
  if (!j.is_object() || j.value("format", "") != "hofem-checkpoint" || !j.contains("key") || !j.contains("state") ||
      !j.contains("step") || !j["state"].is_string() || !j["key"].is_string() || !j["step"].is_number_integer())
    throw std::runtime_error(fmt::format("{}: not a hofem checkpoint record (format, key, step, state)", path.string()));
  if (j["key"].get<std::string>() != key)
    throw std::runtime_error(fmt::format("{}: the checkpoint is of another scene or resolution (key {}, this run's {}); "
                                         "remove the directory to start afresh",
                                         path.string(), j["key"].get<std::string>(), key));
  const std::string state = j["state"].get<std::string>();
  if (state.find('/') != std::string::npos || state.find("..") != std::string::npos)
    throw std::runtime_error(fmt::format("{}: state '{}' is not a file of the checkpoint directory", path.string(), state));
  RunCheckpoint c;
  c.key = key;
  c.state = read_state((fs::path(dir) / state).string());
  if (c.state.key != key || c.state.step != j["step"].get<int>())
    throw std::runtime_error(fmt::format("{}: the record and its state file {} disagree (key or step)", path.string(), state));
  c.record = j.value("record", nlohmann::json::object());
  return c;
}

}  // namespace hofem
