#include "scene/scene_fingerprint.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <fstream>
#include <iterator>

namespace hofem {

namespace {
struct Fnv1a {
  std::uint64_t h = 1469598103934665603ull;
  void add(std::string_view bytes) {
    for (unsigned char c : bytes) h = (h ^ c) * 1099511628211ull;
    h = (h ^ 0xff) * 1099511628211ull;  // a separator: ("ab", "c") differs from ("a", "bc")
  }
};

void add_file(Fnv1a& f, const Scene& s, const std::string& path) {
  if (path.empty()) return;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(fmt::format("{}: cannot read '{}' to fingerprint the scene", s.file, path));
  f.add(std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()));
}
}  // namespace

std::string scene_fingerprint(const Scene& s) {
  Fnv1a f;
  f.add(s.resolved);
  f.add(s.reorient ? "reorient" : "");
  add_file(f, s, s.mesh.file);
  if (s.embedded) add_file(f, s, s.embedded->shape.file);
  return fmt::format("{:016x}", f.h);
}

}  // namespace hofem
