#pragma once
// A dynamic state on disk: time, step, positions and velocities of every node,
// for runs that continue where another stopped (a benchmark's stored mid-run
// state, a checkpoint). The file is one header line of JSON ({"format":
// "hofem-state", "version": 1, "t", "step", "values", "key"}) followed by the
// positions and then the velocities as little-endian IEEE doubles. `key`
// names what the state belongs to (a scene and its resolution, chosen by the
// writer) so that a reader refuses a state of another discretisation.
// Written through AtomicFile: a killed writer leaves the old file or none.
#include <Eigen/Core>

#include <string>

namespace hofem {

struct StoredState {
  std::string key;
  double t = 0.0;
  int step = 0;
  Eigen::VectorXd x, v;  ///< same size, finite
};

void write_state(const std::string& path, const StoredState& state);
/// Throws std::runtime_error naming the file and what is wrong with it (not a
/// state file, truncated, sizes, non-finite values).
StoredState read_state(const std::string& path);

}  // namespace hofem
