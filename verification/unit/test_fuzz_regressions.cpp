// Inputs that once crashed a fuzz target (scripts/fuzz copies every crasher to
// data/fuzz_regressions/<target>/, named by its sha1) and hand-written adversarial
// inputs, replayed on every ctest run. Each must end the way the parser documents:
// a mesh or a scene, or MeshError / SceneError whose message starts with the
// origin; the command line returns an exit status or "run" without throwing. A
// crash takes the test down with it: the file it was replaying is printed first.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "command_line.hpp"
#include "command_line_input.hpp"
#include "io/gmsh_reader.hpp"
#include "scene/scene.hpp"

namespace hofem {
namespace {

namespace fs = std::filesystem;

// The inputs of one target, sorted so that a failure names the same file every run.
std::vector<fs::path> inputs(const std::string& target) {
  const fs::path dir = fs::path(HOFEM_TEST_DATA_DIR) / "fuzz_regressions" / target;
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.is_regular_file()) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

std::string read_bytes(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

// Under a sanitizer or a stack overflow the process dies without gtest's report.
void announce(const std::string& what) {
  std::fprintf(stderr, "replaying %s\n", what.c_str());
  std::fflush(stderr);
}

// What a documented rejection must look like: "<origin>:<...>".
template <class Error>
void expect_documented(const Error& e, const std::string& origin) {
  const std::string what = e.what();
  EXPECT_GT(what.size(), origin.size() + 1);
  EXPECT_EQ(what.rfind(origin + ":", 0), 0u) << what;
}

// Replays every input of a target's folder through `parse`: it must succeed or
// throw the documented Error naming the input, nothing else.
template <class Error, class Parse>
void replay(const std::string& target, Parse parse) {
  const auto files = inputs(target);
  ASSERT_FALSE(files.empty());
  for (const auto& path : files) {
    SCOPED_TRACE(path.string());
    announce(path.string());
    const std::string origin = path.filename().string();
    try {
      parse(read_bytes(path), origin);
    } catch (const Error& e) {
      expect_documented(e, origin);
    } catch (const std::exception& e) {
      ADD_FAILURE() << "undocumented exception: " << e.what();
    } catch (...) {
      ADD_FAILURE() << "non-standard exception";
    }
  }
}

TEST(FuzzRegressions, GmshReader) {
  replay<MeshError>("gmsh_reader", [](const std::string& text, const std::string& origin) { read_gmsh_text(text, origin); });
}

TEST(FuzzRegressions, SceneParser) {
  replay<SceneError>("scene_parser", [](const std::string& text, const std::string& origin) { parse_scene(text, origin); });
}

// Nesting far deeper than any scene, generated rather than committed (~200 KB
// each): a deep value where the parser only checks its type, where an error
// message prints the value (Field::fail with json::dump, which recurses), and
// left unclosed. Kept apart from SceneParser so that its status is visible on its
// own: a stack overflow here was known when the fuzz targets were added.
TEST(FuzzRegressions, DeepNesting) {
  constexpr int kDepth = 100000;
  const std::string arrays = std::string(kDepth, '[') + std::string(kDepth, ']');
  std::string objects;
  for (int i = 0; i < kDepth; ++i) objects += "{\"a\":";
  objects += "0" + std::string(kDepth, '}');
  const std::pair<const char*, std::string> cases[] = {
      {"mesh = deep arrays", "{\"mesh\": " + arrays + "}"},
      {"mesh = unclosed arrays", "{\"mesh\": " + std::string(kDepth, '[')},
      {"name = deep arrays (printed in the error)", "{\"name\": " + arrays + "}"},
      {"mesh.box.min = deep objects (printed in the error)",
       "{\"mesh\": {\"box\": {\"min\": " + objects + "}}}"},
  };
  for (const auto& [label, text] : cases) {
    SCOPED_TRACE(label);
    announce(label);
    try {
      parse_scene(text, "deep.json");
      ADD_FAILURE() << "accepted";
    } catch (const SceneError& e) {
      expect_documented(e, "deep.json");
    } catch (const std::exception& e) {
      ADD_FAILURE() << "undocumented exception: " << e.what();
    }
  }
}

TEST(FuzzRegressions, CommandLine) {
  const auto files = inputs("command_line");
  ASSERT_FALSE(files.empty());
  std::FILE* null = std::fopen("/dev/null", "w");
  ASSERT_NE(null, nullptr);
  for (const auto& path : files) {
    SCOPED_TRACE(path.string());
    announce(path.string());
    const auto words = fuzz::command_line_words(read_bytes(path));
    const auto argv = fuzz::argv_of(words);
    cli::CommandLine cl;
    int status = 0;
    EXPECT_NO_THROW(status = cli::parse_command_line(static_cast<int>(words.size()), argv.data(), cl, null, null));
    EXPECT_TRUE(status == -1 || status == 0 || status == 2) << status;
    if (status == -1) {
      EXPECT_FALSE(cl.subcommand.empty());
    }
  }
  std::fclose(null);
}

}  // namespace
}  // namespace hofem
