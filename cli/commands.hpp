#pragma once
// The work behind each `hofem` subcommand, separate from argument parsing.
#include <stdexcept>
#include <string>
#include <vector>

namespace hofem::cli {

/// Invalid user input detected after parsing (unknown cell name, ...): exit status 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Applies --limit NAME=VALUE options (io/input_file.hpp) before any input is read;
/// a bad one is a UsageError.
void apply_limits(const std::vector<std::string>& limits);

/// Sentinel for "option not given".
inline constexpr int kUnset = -1000000;

struct QuadratureOptions {
  std::string cell;
  int degree = kUnset;
  bool json = false;
  bool list = false;
};
int run_quadrature(const QuadratureOptions& o);

struct BasisOptions {
  std::string cell;
  int order = 1;
  bool json = false;
};
int run_basis(const BasisOptions& o);

struct MeshOptions {
  int box = 0;
  std::string msh;
  std::string cell = "tet";
  int order = kUnset;
  std::string vtu;
  std::string vtu_format = "binary";  ///< ascii | binary | zlib (io/vtu_writer.hpp VtuFormat)
  bool json = false;
  int partition = 0;  ///< > 0: also partition the elements into this many parts (RCB) and report the quality
  std::vector<std::string> limits;  ///< --limit NAME=VALUE: raised input caps (io/input_file.hpp)
  bool reorient = false;            ///< flip straight inverted elements of --msh, with a warning
};
int run_mesh(const MeshOptions& o);

struct MmsOptions {
  std::string problem;
  std::string order = "1";  ///< one order or a comma list ("1,2,3"): every order x n runs
  std::string n = "4";      ///< cubes per side, one or a comma list
  std::string cell = "tet";
  bool perturbed = false;
  std::string solver = "auto";
  bool json = false;
  std::string vtu;
  std::string vtu_format = "binary";  ///< ascii | binary | zlib
  bool distributed = false;  ///< over the MPI ranks (run under mpirun -np K); rank 0 prints
  std::string krylov = "pcg";   ///< distributed solver (DistributedSolverOptions)
  std::string amg = "amg";
  bool rigid_body_modes = false;
  std::vector<std::string> limits;  ///< --limit NAME=VALUE
  std::string export_matrix;  ///< --export-matrix PREFIX (one linear, serial run)
};
int run_mms(const MmsOptions& o);

struct VerifyOptions {
  std::string out = "reports/verification.json";
  std::string group;
  bool quiet = false;
  std::string convergence = "ci";
  std::string junit;  ///< JUnit XML path, empty: none
  bool list = false;  ///< print the families (id, label, groups) and exit
  /// The convergence study's tidy table goes to PREFIX.csv and PREFIX.json;
  /// empty: "convergence" in the directory of `out`.
  std::string convergence_table;
};
// `hofem verify` is run by its own executable, hofem-verify
// (verification/verify_main.cpp), so that this one does not link the
// verification suite; main.cpp hands the arguments over.

struct RunOptions {
  std::string scene;
  std::string out;
  bool no_frames = false;
  bool final_frame = false;           ///< with --no-frames: still write the last state as final.vtu
  std::string vtu_format = "binary";  ///< ascii | binary | zlib
  bool distributed = false;  ///< over the MPI ranks (mpirun -np K hofem run ... --distributed)
  std::vector<std::string> limits;  ///< --limit NAME=VALUE
  bool reorient = false;            ///< flip straight inverted elements of the scene's .msh files, with a warning
  std::vector<std::string> set;     ///< --set key.path=VALUE: SceneOverrides (scene.hpp), applied before validation
  bool check = false;               ///< --check: validate only (scene_commands.hpp)
  bool print_defaults = false;      ///< --print-defaults: print the default scene and exit
  std::string checkpoint_every;     ///< --checkpoint-every: "N" steps or "Ns" seconds (OUT/checkpoint/)
  bool resume = false;              ///< --resume: continue from OUT/checkpoint/ when there is one
  std::string save_state;           ///< --save-state PATH: the last state as a state file
};
/// Exit status 0 when every step succeeded, 1 when a step failed (stats.json
/// still written), 2 for an invalid scene (the message names the file and key).
int run_scene_file(const RunOptions& o);

struct StudyOptions {
  std::string study;
  std::string out;                  ///< default: reports/studies/NAME (NAME from the study file)
  std::vector<std::string> limits;  ///< --limit NAME=VALUE
  bool resume = false;              ///< --resume: reuse finished runs' records, continue stopped runs
  bool extended = false;            ///< --extended: run the study's "extended" runs too
};
/// Runs a study (core/study/study_file.hpp) and writes study.json and summary.md.
/// Exit status 0 when the study ran (runs that fail are rows of the table), 2 for
/// an invalid study or scene, 1 when the reference fails.
int run_study_file(const StudyOptions& o);

struct ChoicesOptions {
  bool json = false;
};
/// Prints every registry: the materials, integrators, linear solvers,
/// preconditioners, BoomerAMG variants and the element orders of each cell,
/// with what each is (cli/choices.cpp); --json for scripts and ctest
/// registries.lists_agree.
int run_choices(const ChoicesOptions& o);

}  // namespace hofem::cli
