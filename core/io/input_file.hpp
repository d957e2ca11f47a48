#pragma once
// Reading an input file (a mesh or a scene) safely, and the caps every input is
// held to before anything is allocated for it.
//
// An input path must name a regular file: a directory, character device
// (/dev/zero), FIFO, socket or block device is refused before a byte is read, so
// a scene that points at /dev/zero fails at once instead of reading for ever.
// Standard input is read only when asked for explicitly, by the path "-".
// Sizes are checked against InputLimits before reading; a user with a larger
// problem raises a cap (`--limit NAME=VALUE` on the command line, listed by
// `input_limit_names()`), it is never silently truncated.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace hofem {

/// An input refused before it is parsed: the message names the file or option.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Caps on what an input may ask for. Defaults are ~10x the largest problem this
/// machine class (24 GiB) solves, so they stop typos and hostile files (a box of
/// 1000^3 cells, a 10^5-deep JSON array) rather than real work.
struct InputLimits {
  std::uint64_t mesh_file_bytes = 2ull << 30;     ///< mesh-file-mb: an ASCII .msh of ~2e7 Tet4
  std::uint64_t scene_file_bytes = 1ull << 20;    ///< scene-file-kb: scenes are hand-written
  long long elements = 20'000'000;                ///< elements: of a mesh read or generated
  long long nodes = 50'000'000;                   ///< nodes: of a mesh read or generated
  int order = 10;                                 ///< order: a tet's Lagrange order (P10: 286 nodes)
  int json_depth = 32;                            ///< json-depth: the scene format nests 5 deep
  long long boundary_entries = 10'000;            ///< boundary-entries: a scene's "boundary" array
};

/// The process-wide caps (the command line raises them once, before any input
/// is read; the readers of every layer consult them).
InputLimits& input_limits();

/// Sets one cap from "NAME=VALUE" (names as in input_limit_names(); VALUE a
/// positive number, e.g. "elements=5e7"). Throws std::invalid_argument naming
/// the valid names or the bad value.
void set_input_limit(std::string_view name_equals_value, InputLimits& limits = input_limits());

/// "mesh-file-mb, scene-file-kb, elements, nodes, json-depth, boundary-entries".
std::vector<std::string> input_limit_names();

/// The whole content of `path`, or of standard input when path is "-". Throws
/// InputError "<path>: cannot read <what>: <reason>" for a missing or unreadable
/// path, a path that is not a regular file, or content over max_bytes.
std::string read_input_file(const std::string& path, std::string_view what, std::uint64_t max_bytes);

/// "N elements exceed the cap of M (raise it with --limit elements=N)" when a
/// mesh of this size would be over the caps, else empty; asked before a
/// generator allocates.
std::string mesh_size_excess(long long elements, long long nodes);

}  // namespace hofem
