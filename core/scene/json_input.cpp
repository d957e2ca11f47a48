// Reading JSON inputs (scenes, studies) with messages that name the file, the
// line or the key path (json_input.hpp).
#include "scene/json_input.hpp"

#include "io/input_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <set>

namespace hofem {

using json = nlohmann::json;

namespace {

// nlohmann's message without its "[json.exception.parse_error.101] " tag.
std::string without_tag(const char* what) {
  const std::string_view w(what);
  const std::size_t end = w.rfind("] ", 40);
  return std::string(w.substr(w.substr(0, 1) == "[" && end != std::string_view::npos ? end + 2 : 0));
}

}  // namespace

std::string read_json_file(const std::string& path, const char* what) {
  try {
    return read_input_file(path, what, input_limits().scene_file_bytes);
  } catch (const InputError& e) {
    throw SceneError(e.what());
  }
}

std::string brief(const json& j) {
  std::string s = j.dump();
  if (s.size() > 60) s = s.substr(0, 60) + "...";
  return s;
}

void check_nesting(const std::string& text, const std::string& origin) {
  const int cap = input_limits().json_depth;
  int depth = 0;
  long line = 1;
  bool in_string = false, escaped = false;
  for (const char c : text) {
    if (c == '\n') ++line;
    // nlohmann's parser stops at a NUL as at the end of the text, silently
    // ignoring the rest: a NUL is refused (a scene is text).
    if (c == '\0') throw SceneError(fmt::format("{}: line {}: a NUL byte: not a text file", origin, line));
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > cap)
        throw SceneError(fmt::format("{}: line {}: JSON nested deeper than {} levels (the cap; raise it with --limit "
                                     "json-depth=N)",
                                     origin, line, cap));
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

json parse_json(const std::string& text, const std::string& origin, const std::string& document) {
  struct Frame {
    bool array;
    std::string key;
    long index;
    std::set<std::string> keys;  // seen in this object: JSON allows duplicates, the last would win silently
  };
  std::vector<Frame> frames;
  auto path = [&frames, &document] {
    std::string p;
    for (const Frame& f : frames)
      p += f.array ? fmt::format("[{}]", f.index) : (p.empty() ? f.key : "." + f.key);
    return p.empty() ? document : p;
  };
  auto next_item = [&frames] {
    if (!frames.empty() && frames.back().array) ++frames.back().index;
  };
  const json::parser_callback_t track = [&](int, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start: frames.push_back({false, "", 0, {}}); break;
      case json::parse_event_t::array_start: frames.push_back({true, "", 0, {}}); break;
      case json::parse_event_t::key:
        frames.back().key = parsed.get<std::string>();
        if (!frames.back().keys.insert(frames.back().key).second)
          throw SceneError(fmt::format("{}: {}: the key appears twice in its object", origin, path()));
        break;
      case json::parse_event_t::value: next_item(); break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        frames.pop_back();
        next_item();
        break;
    }
    return true;
  };
  try {
    return json::parse(text, track);
  } catch (const json::parse_error& e) {
    // e.byte is the offset of the error; report the line.
    const size_t byte = std::min<size_t>(e.byte, text.size());
    const long line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(byte > 0 ? byte - 1 : 0), '\n');
    throw SceneError(fmt::format("{}: line {}: not valid JSON ({})", origin, line, without_tag(e.what())));
  } catch (const json::out_of_range& e) {
    // The only range error of the parser: a number beyond double's range.
    throw SceneError(fmt::format("{}: {}: a number out of the range of a double (|x| < 1.8e308): {}", origin, path(),
                                 without_tag(e.what())));
  } catch (const json::exception& e) {
    throw SceneError(fmt::format("{}: {}: cannot read the JSON: {}", origin, path(), without_tag(e.what())));
  }
}


}  // namespace hofem
