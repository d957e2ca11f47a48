// Output is complete or absent: AtomicFile renames a finished temporary file
// over the real name; a process killed mid-write (the SIGKILL test hook) leaves
// only a ".partial-" file and any older complete file untouched. A failed scene
// run leaves a stats.json that says it failed and why; a run into a folder with
// an older run's frames removes them first.
#include "io/atomic_file.hpp"
#include "scene/scene.hpp"
#include "scene/scene_runner.hpp"

#include <gtest/gtest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

namespace hofem {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct Scratch {
  fs::path dir = fs::temp_directory_path() / ("hofem_atomic_" + std::to_string(::getpid()));
  Scratch() { fs::create_directories(dir); }
  ~Scratch() { fs::remove_all(dir); }
};

std::vector<std::string> files_in(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(AtomicFile, CommitReplacesAndAnAbandonedWriteLeavesNothing) {
  Scratch s;
  const std::string path = (s.dir / "out.json").string();
  write_file_atomically(path, "old\n");
  {
    AtomicFile f(path);
    f.write("new, but never committed");
  }  // destroyed without commit: as if an exception unwound the writer
  EXPECT_EQ(slurp(path), "old\n");
  EXPECT_EQ(files_in(s.dir), std::vector<std::string>{"out.json"});
  write_file_atomically(path, "new\n");
  EXPECT_EQ(slurp(path), "new\n");
}

TEST(AtomicFile, SigkillMidWriteLeavesTheOlderFileWhole) {
  Scratch s;
  const std::string path = (s.dir / "stats.json").string();
  const std::string old = "{\"complete\": true}\n";
  write_file_atomically(path, old);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::setenv("HOFEM_TEST_KILL_WRITING", "stats.json", 1);
    write_file_atomically(path, std::string(100000, 'x'));
    std::_Exit(0);  // not reached: the hook kills the child halfway through the write
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << "the hook did not kill the writer";
  EXPECT_EQ(slurp(path), old);  // the real name still holds the complete older file
  const std::string partial = fmt::format("stats.json.partial-{}", child);
  EXPECT_EQ(files_in(s.dir), (std::vector<std::string>{"stats.json", partial}));
  EXPECT_EQ(fs::file_size(s.dir / partial), 50000u);  // killed halfway: the hook fired mid-write
}

TEST(SceneOutput, FailedRunWritesStatsSayingWhyAndOldFramesAreCleared) {
  Scratch s;
  // An older run's output: frames and an index that the new run must not mix with its own.
  for (const char* old : {"frame_00040.vtu", "frame_00040_surface.vtu", "inverted.pvd", "stats.json",
                          "stats.json.partial-12", "notes.txt"})
    std::ofstream(s.dir / old) << "old\n";
  const Scene scene = read_scene(std::string(HOFEM_TEST_DATA_DIR) + "/bad_scene_inverted_tet10.json");
  EXPECT_THROW(run_scene(scene, s.dir.string()), SceneError);
  // Only the user's own file and the failed run's stats.json remain.
  EXPECT_EQ(files_in(s.dir), (std::vector<std::string>{"notes.txt", "stats.json"}));
  const nlohmann::json st = nlohmann::json::parse(slurp(s.dir / "stats.json"));
  EXPECT_EQ(st.at("status"), "failed");
  EXPECT_EQ(st.at("ok"), false);
  EXPECT_NE(st.at("message").get<std::string>().find("bad_inverted_tet10.msh:35: element 7: inverted"),
            std::string::npos)
      << st.dump();
}

}  // namespace
}  // namespace hofem
