#pragma once
// Checkpoints of a time-stepping run, so that a killed run continues where it
// was instead of from rest (hofem run --resume, and a study's runs).
//
// A checkpoint is a directory holding
//   state-<step>.state   positions, velocities, time and step (io/state_file.hpp)
//   checkpoint.json      the commit record: the scene's fingerprint, the step,
//                        the state file's name, and what the run recorded so far
//                        (stats.json's per-step rows, the frames written, the
//                        deformation record), plus the caller's own record
// written in that order, each through an atomic rename: a run killed at any
// instant leaves the last complete checkpoint readable (the record names a
// state file that was complete before the record was written; older state
// files are removed only after it).
//
// Resumed runs repeat exactly what the interrupted one would have done when
// every solve is deterministic (CHOLMOD, or a Krylov method whose set-up is
// rebuilt at every Newton iteration): the state, the time and the step are
// restored bit for bit. A Krylov solver that reuses its set-up across steps
// starts the resumed part on a fresh set-up (and the amortised rule decides by
// measured seconds in any case), so those runs agree to the Newton tolerance,
// not bitwise.
#include "io/state_file.hpp"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>

namespace hofem {

struct RunCheckpoint {
  std::string key;  ///< the scene's fingerprint (scene_fingerprint.hpp)
  StoredState state;
  nlohmann::json record = nlohmann::json::object();  ///< per-step rows, frames, ...
};

/// Writes the checkpoint into `dir` (created if missing) atomically; removes
/// the state files of earlier checkpoints. Throws std::runtime_error naming
/// the file on an I/O error.
void write_checkpoint(const std::string& dir, const RunCheckpoint& c);

/// The checkpoint in `dir`, or nullopt when there is none. Throws
/// std::runtime_error naming the file when one is there but unreadable, or
/// belongs to another scene (its key is not `key`).
std::optional<RunCheckpoint> read_checkpoint(const std::string& dir, const std::string& key);

}  // namespace hofem
