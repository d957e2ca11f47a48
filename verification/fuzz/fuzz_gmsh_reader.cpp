// libFuzzer target: the Gmsh .msh reader on arbitrary text. The reader documents
// that every malformed input throws MeshError (core/io/gmsh_reader.hpp); any
// other exception escaping, a crash, a leak or undefined behaviour is a finding.
#include "io/gmsh_reader.hpp"
#include "mesh/mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    hofem::read_gmsh_text(text, "fuzz.msh");
  } catch (const hofem::MeshError&) {
    // the documented rejection
  }
  return 0;
}
