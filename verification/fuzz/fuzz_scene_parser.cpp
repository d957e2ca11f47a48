// libFuzzer target: the scene parser on arbitrary text. parse_scene documents
// SceneError for every invalid scene (core/scene/scene.hpp); it neither builds the
// mesh nor opens files, so the run stays in the parser. Any other exception, a
// crash, a leak or undefined behaviour is a finding.
#include "scene/scene.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    hofem::parse_scene(text, "fuzz.json");
  } catch (const hofem::SceneError&) {
    // the documented rejection
  }
  return 0;
}
