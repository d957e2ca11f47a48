#include "study/study_file.hpp"

#include "scene/json_input.hpp"

#include <algorithm>
#include <filesystem>
#include <set>

namespace hofem {

namespace {

std::vector<std::string> strings(const Field& f) {
  if (!f.raw().is_array()) f.fail("must be an array of strings");
  std::vector<std::string> out;
  for (size_t i = 0; i < f.raw().size(); ++i) out.push_back(f.item(i).string());
  return out;
}

std::string run_name(const Field& f) {
  const std::string name = f.string();
  if (name.empty() || name.size() > 64 ||
      name.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789._-") != std::string::npos ||
      name[0] == '.')
    f.fail(fmt::format("= '{}' must be 1-64 of the characters A-Z a-z 0-9 . _ - (it names a folder)", name));
  return name;
}

// The run's scene: the study's overrides, then the run's; a scene error is
// reported with the study file and the run it came from.
Scene run_scene_of(const Study& s, const Field& where, const SceneOverrides& own) {
  SceneOverrides all = s.overrides;
  all.insert(all.end(), own.begin(), own.end());
  try {
    return read_scene(s.scene_file, all);
  } catch (const SceneError& e) {
    where.fail(fmt::format("gives a scene that is not valid: {}", e.what()));
  }
}

StudyRun parse_run(const Field& f, const Study& s, bool reference) {
  if (reference) f.keys({"name", "overrides", "coarser"});
  else f.keys({"name", "family", "overrides", "extended"});
  StudyRun r;
  r.name = reference && !f.has("name") ? "reference" : run_name(f.at("name"));
  r.family = reference ? "reference" : f.at("family").string();
  if (r.family.empty()) f.at("family").fail("must not be empty");
  if (f.has("overrides")) r.overrides = strings(f.at("overrides"));
  if (!reference && f.has("extended")) r.extended = f.at("extended").boolean();
  r.scene = run_scene_of(s, f.has("overrides") ? f.at("overrides") : f, r.overrides);
  return r;
}

std::vector<double> positive_values(const Field& f, double hi, bool ascending) {
  if (!f.raw().is_array() || f.raw().empty()) f.fail("must be a non-empty array of numbers");
  std::vector<double> out;
  for (size_t i = 0; i < f.raw().size(); ++i) {
    out.push_back(f.item(i).number(0.0, hi, true));
    if (ascending && i > 0 && out[i] <= out[i - 1]) f.item(i).fail("must be larger than the value before it (ascending)");
  }
  return out;
}

}  // namespace

Study parse_study(const std::string& text, const std::string& origin) {
  check_nesting(text, origin);
  const nlohmann::json j = parse_json(text, origin, "the study");
  const Field root(j, "", origin, "the study");
  root.keys({"$schema", "name", "scene", "overrides", "frames", "metric", "thresholds", "subdivisions", "reference",
             "runs"});
  // "$schema": an editor's pointer to study.schema.json; not used here.
  if (root.has("$schema")) root.at("$schema").string();
  Study s;
  s.file = origin;
  s.name = run_name(root.at("name"));
  s.scene_file = root.at("scene").string();
  if (std::filesystem::path(s.scene_file).is_relative())
    s.scene_file = (std::filesystem::path(origin).parent_path() / s.scene_file).lexically_normal().string();
  if (root.has("overrides")) s.overrides = strings(root.at("overrides"));
  if (root.has("metric")) s.metric = root.at("metric").choice({"surface_rms", "displacement_rms"});
  s.thresholds = positive_values(root.at("thresholds"), 1e300, false);
  std::sort(s.thresholds.begin(), s.thresholds.end());
  if (root.has("subdivisions")) s.subdivisions = root.at("subdivisions").integer(1, 64);

  s.reference = parse_run(root.at("reference"), s, true);
  const Scene& scene = s.reference.scene;
  if (scene.is_static) {
    if (root.has("frames")) root.at("frames").fail("does not apply to a static scene (it is measured at its solution)");
    s.frames = {1.0};
  } else {
    s.frames = positive_values(root.at("frames"), scene.duration * (1 + 1e-12), true);
  }
  if (root.at("reference").has("coarser")) {
    const Field c = root.at("reference").at("coarser");
    const SceneOverrides overrides = strings(c);
    s.coarser_reference = StudyRun{.name = "reference-coarser", .family = "reference", .overrides = overrides,
                                   .scene = run_scene_of(s, c, overrides)};
  }
  const Field runs = root.at("runs");
  if (!runs.raw().is_array() || runs.raw().empty()) runs.fail("must be a non-empty array of runs");
  std::set<std::string> names{s.reference.name, "reference-coarser"};
  for (size_t i = 0; i < runs.raw().size(); ++i) {
    s.runs.push_back(parse_run(runs.item(i), s, false));
    if (!names.insert(s.runs.back().name).second)
      runs.item(i).at("name").fail(fmt::format("= '{}' is used twice (names are folders)", s.runs.back().name));
    const Scene& r = s.runs.back().scene;
    if (r.is_static != scene.is_static || (!r.is_static && r.duration < s.frames.back()))
      runs.item(i).fail("must keep the reference's integrator kind and last at least until the last frame");
  }
  return s;
}

Study read_study(const std::string& path) {
  return parse_study(read_json_file(path, "the study file"), path == "-" ? "<stdin>" : path);
}

}  // namespace hofem
