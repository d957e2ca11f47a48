// Provenance and progress: the context every JSON output carries, and the
// progress lines long runs print.
#include "provenance/progress.hpp"
#include "provenance/provenance.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <regex>
#include <string>
#include <thread>

namespace hofem {
namespace {

TEST(Provenance, ContextHasEveryKeyWithItsType) {
  const nlohmann::json c = provenance_context("ci");
  EXPECT_EQ(c["schema_version"], kOutputSchemaVersion);
  EXPECT_EQ(c["preset"], "ci");
  EXPECT_TRUE(std::regex_match(c["commit"].get<std::string>(), std::regex("[0-9a-f]{40}|unknown"))) << c["commit"];
  EXPECT_TRUE(c["dirty"].is_boolean());
  EXPECT_TRUE(std::regex_match(c["date"].get<std::string>(), std::regex(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ)")));
  EXPECT_TRUE(std::regex_match(c["hofem_version"].get<std::string>(), std::regex(R"(\d+\.\d+\.\d+)")));
  EXPECT_FALSE(c["compiler"].get<std::string>().empty());
  EXPECT_GE(c["threads"].get<int>(), 1);
  EXPECT_EQ(c.size(), 13u);  // the keys verification.schema.json requires
}

TEST(Provenance, VersionTextNamesVersionCommitAndBuild) {
  const std::string v = version_text();
  EXPECT_EQ(v.rfind("hofem " + std::string(hofem_version()) + " (commit ", 0), 0u) << v;
  EXPECT_NE(v.find(" build, "), std::string::npos) << v;
}

TEST(ProgressLog, FormatsDurations) {
  EXPECT_EQ(ProgressLog::format_seconds(4.4), "4 s");
  EXPECT_EQ(ProgressLog::format_seconds(65.2), "1 min 05 s");
  EXPECT_EQ(ProgressLog::format_seconds(3 * 3600 + 7 * 60 + 1), "3 h 07 min");
  EXPECT_EQ(ProgressLog::format_seconds(-1.0), "?");
}

std::string read_all(std::FILE* f) {
  std::rewind(f);
  std::string text;
  for (int c; (c = std::fgetc(f)) != EOF;) text += static_cast<char>(c);
  return text;
}

// Off a terminal (a file here): a line per stage with the share done and the
// estimate, silent per-step updates, and a heartbeat naming the stage when a
// stage outlasts the interval (0.5 s here; the heartbeat wakes once a second,
// so 2.5 s leaves room for two wake-ups on a loaded machine).
TEST(ProgressLog, StagesHeartbeatAndDoneOffATerminal) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  {
    ProgressLog log("job", f, 0.5);
    log.stage("[1/2] first", 0.0);
    log.update("step 3/4", 0.5);  // no line of its own off a terminal
    std::this_thread::sleep_for(std::chrono::milliseconds(2500));
    log.note("a result");
    log.done("2 stages");
  }
  const std::string text = read_all(f);
  std::fclose(f);
  EXPECT_NE(text.find("job: [1/2] first | 0 s elapsed\n"), std::string::npos) << text;
  EXPECT_EQ(text.find("job: step 3/4 |"), std::string::npos) << text;
  EXPECT_TRUE(std::regex_search(text, std::regex(R"(job: still in step 3/4 \| \d s elapsed, ~\d s left \(50 % done\))")))
      << text;
  EXPECT_NE(text.find("job: a result |"), std::string::npos) << text;
  EXPECT_TRUE(std::regex_search(text, std::regex(R"(job: done: 2 stages \| \d s elapsed\n$)"))) << text;
}

}  // namespace
}  // namespace hofem
