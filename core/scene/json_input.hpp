#pragma once
// Reading JSON inputs (scene files, study files) so that every error names the
// file and the line or key path: "scene.json: line 3: not valid JSON (...)",
// "study.json: runs[2].overrides must be an array of strings". Errors are
// SceneError (scene/scene.hpp).
#include "scene/scene.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <initializer_list>
#include <set>
#include <string>
#include <vector>

namespace hofem {

/// A value for a message: short, because a wrong value may be a 1 MB array.
std::string brief(const nlohmann::json& j);

/// Refuses NUL bytes and nesting deeper than the cap (input_limits().json_depth)
/// before parsing: our formats nest 5 levels, and a value nested 10^5 deep would
/// exhaust the stack of any recursive consumer (nlohmann's dump and destructor
/// included). Brackets inside strings do not count.
void check_nesting(const std::string& text, const std::string& origin);

/// The text of a scene or study file (read_input_file's checks: regular files
/// only, "-" is stdin, at most the scene-file cap); errors are SceneError.
/// `what` names it in messages ("the study file").
std::string read_json_file(const std::string& path, const char* what);

/// Parses the JSON, tracking the key path of the value being read so that a
/// number the parser cannot hold (1e999) is reported with its key and a key that
/// appears twice in its object is refused; `document` names the top level.
nlohmann::json parse_json(const std::string& text, const std::string& origin, const std::string& document = "the scene");

// A JSON value with its key path, whose accessors validate and name the key.
class Field {
 public:
  /// `origin` names the file; `document` is what an empty path is called in messages.
  Field(const nlohmann::json& j, std::string path, const std::string& origin, std::string document = "the scene")
      : j_(j), path_(std::move(path)), origin_(origin), document_(std::move(document)) {}

  [[noreturn]] void fail(const std::string& what) const {
    throw SceneError(fmt::format("{}: {} {}", origin_, path_.empty() ? document_ : path_, what));
  }
  const nlohmann::json& raw() const { return j_; }

  /// Requires an object whose keys are all in `allowed`.
  void keys(std::initializer_list<const char*> allowed) const {
    if (!j_.is_object()) fail("must be an object");
    std::set<std::string> ok(allowed.begin(), allowed.end());
    for (const auto& [k, v] : j_.items())
      if (!ok.count(k))
        throw SceneError(fmt::format("{}: key '{}' is unknown (valid: {})", origin_, join(k),
                                     fmt::join(std::vector<std::string>(ok.begin(), ok.end()), ", ")));
  }
  bool has(const std::string& k) const { return j_.is_object() && j_.contains(k); }
  Field at(const std::string& k) const {
    if (!has(k)) throw SceneError(fmt::format("{}: key '{}' is missing", origin_, join(k)));
    return Field(j_.at(k), join(k), origin_, document_);
  }
  Field item(size_t i) const { return Field(j_.at(i), fmt::format("{}[{}]", path_, i), origin_, document_); }

  double number(double lo, double hi, bool lo_open = false, bool hi_open = false) const {
    if (!j_.is_number()) fail(fmt::format("must be a number (got {})", brief(j_)));
    const double v = j_.get<double>();
    if (!std::isfinite(v) || (lo_open ? v <= lo : v < lo) || (hi_open ? v >= hi : v > hi))
      fail(fmt::format("= {} is out of range {}{}, {}{}", v, lo_open ? "(" : "[", lo, hi, hi_open ? ")" : "]"));
    return v;
  }
  int integer(int lo, int hi) const {
    if (!j_.is_number_integer()) fail(fmt::format("must be an integer (got {})", brief(j_)));
    // A number_unsigned above LLONG_MAX would wrap in get<long long>().
    if (j_.is_number_unsigned() && j_.get<unsigned long long>() > static_cast<unsigned long long>(hi))
      fail(fmt::format("= {} is out of range [{}, {}]", j_.get<unsigned long long>(), lo, hi));
    const long long v = j_.get<long long>();
    if (v < lo || v > hi) fail(fmt::format("= {} is out of range [{}, {}]", v, lo, hi));
    return static_cast<int>(v);
  }
  bool boolean() const {
    if (!j_.is_boolean()) fail(fmt::format("must be true or false (got {})", brief(j_)));
    return j_.get<bool>();
  }
  std::string string() const {
    if (!j_.is_string()) fail(fmt::format("must be a string (got {})", brief(j_)));
    return j_.get<std::string>();
  }
  std::string choice(const std::vector<std::string>& valid) const {
    const std::string s = string();
    for (const auto& v : valid)
      if (v == s) return s;
    fail(fmt::format("= '{}' is not one of: {}", s, fmt::join(valid, ", ")));
  }
  Eigen::Vector3d vec3() const {
    if (!j_.is_array() || j_.size() != 3) fail(fmt::format("must be an array of 3 numbers (got {})", brief(j_)));
    Eigen::Vector3d v;
    for (int i = 0; i < 3; ++i) v[i] = item(i).number(-1e300, 1e300);
    return v;
  }

 private:
  std::string join(const std::string& k) const { return path_.empty() ? k : path_ + "." + k; }
  const nlohmann::json& j_;
  std::string path_;
  const std::string& origin_;  // outlives the Field: the parser's argument
  std::string document_;
};


}  // namespace hofem
