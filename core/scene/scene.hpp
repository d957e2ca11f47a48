#pragma once
// A scene: everything one run needs, read from a JSON file (scripts/scenes/ has
// the built-in ones). Every key is validated before any work starts: unknown
// keys, wrong types and out-of-range values raise SceneError naming the file and
// the key path ("cantilever.json: material.poisson = 0.5 is out of range (-1, 0.5)").
// The reference of every key (type, default, range) is SCENE_FORMAT.md, generated
// by scripts/schema_docs.py from the JSON Schema scene.schema.json beside this
// file; ctest schema.* checks that schema against this parser.
//
// {
//   "$schema": "../../core/scene/scene.schema.json",  (optional: for editors; ignored)
//   "name": "cantilever",
//   "mesh": {"box": {"min": [0,0,0], "max": [4,1,1], "cells": [8,2,2]}, "cell": "tet", "order": 2}
//        or {"tube": {"r_in": 0.5, "r_out": 1, "height": 3, "cells": [2, 16, 8]}, "cell": "hex", "order": 2}
//        or {"torus": {"major_radius": 1.5, "r_in": 0.25, "r_out": 0.5, "cells": [2, 24, 12]}, "cell": "tet", "order": 2}
//           (a hollow torus about z: cells radial, around z, around the tube; node sets inner, outer)
//        or {"file": "ball.msh", "order": 2}          (a P1 .msh is upgraded to the order)
//   "material": {"model": "stable-neohookean", "young": 1e6, "poisson": 0.45, "density": 1000},
//   "integrator": "implicit-euler" | ... | "static",
//   "dt": 0.01, "duration": 1.0,                    (not for "static")
//   "mass": "lumped" | "consistent", "lumping": "row-sum" | "hrz",          (optional)
//   "solver": {"linear": "auto", "krylov_iterations": 12, "newton_rtol": 1e-8, "newton_max_iterations": 50,
//              "eisenstat_walker": false,
//              "distributed": {"krylov": "pcg" | "gmres", "amg": "amg" | "amg-nodal" | "amg-aggressive",
//                              "rigid_body_modes": false, "gmres_restart": 50}},   (optional)
//              (distributed: hypre's solver in runs with --distributed)
//              (krylov_iterations: every linear solve runs exactly that many
//               iterations of a Krylov solver and takes the iterate, converged
//               or not - a fixed budget per solve; time-stepping scenes only)
//   "gravity": [0, 0, -9.81],                                             (optional)
//   "damping": {"alpha": 0, "beta": 0},                                   (optional)
//   "boundary": [{"nodes": "xmin", "motion": "fixed"},
//                {"nodes": {"box": {"min": [..], "max": [..]}},
//                 "motion": {"rotate": {"point": [..], "axis": [..], "omega": 1, "until": 2}}},
//                {"nodes": "xmax", "motion": {"translate": {"velocity": [..], "until": 1}}, "release": 1}],
//                (rotate also takes "velocity": the axis moves, a screw motion; "release": the
//                 nodes become free at that time, like a slingshot's)
//   "floor": {"height": 0, "normal": [0,0,1], "stiffness": 1e7},          (optional)
//   "initial_velocity": [0, 0, 0],                                        (optional)
//   "output": {"every": 1},                        (a frame every N steps; optional)
//   "embedded": {"file": "../meshes/ball.msh"}                            (optional, below)
//            or {"tube": {"r_in": .., "r_out": .., "height": .., "cells": [..]}}
//            or {"box": {"min": [..], "max": [..], "cells": [..]}},
//               with optional "drop_fraction": 1e-4, "stabilisation": 1e-6, "simplify": true,
//               "stiffness_degree": N
// }
//
// Embedded scenes (finite cell method, Longva et al. 2020 §3.2, §5.3): "embedded" gives
// the body's geometry as tetrahedra - the generators' Tet4 meshes, or a .msh of
// tetrahedra of any order of which only the vertex tets are used - and "mesh" is
// then the background that carries the displacement: a box grid (hex or tet, any
// order) or a .msh of straight-sided cells; a tube is refused (its cells are
// curved or not parallelepipeds, and the cut-cell rules need affine cells). The
// runner integrates over the geometry only (finite-cell rules built once), drops
// cut cells whose volume fraction is below drop_fraction and adds the full cell's
// Gauss points at weight `stabilisation` to the other cut cells, simplifies the
// cut cells' stiffness rules when `simplify`, the added Gauss points included
// (embedded/finite_cell_quadrature.hpp).
// The geometry must lie inside the background. Boundary selections ("box" and
// named sets) pick BACKGROUND nodes: put the embedded body's clamped faces on
// grid planes and select those planes' nodes (e.g. "zmin"); background nodes of
// cells that integrate nothing are held at rest.
#include "dynamics/dynamic_elasticity.hpp"
#include "mesh/mesh.hpp"

#include <Eigen/Core>

#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace hofem {

class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct SceneBoundary {
  std::string set;                       ///< a named node set, or empty when `box` is used
  std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>> box;  ///< nodes inside [min, max]
  std::string motion = "fixed";          ///< "fixed", "translate" or "rotate"
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  ///< translate
  Eigen::Vector3d point = Eigen::Vector3d::Zero(), axis = Eigen::Vector3d::UnitZ();  ///< rotate
  double omega = 0.0;                    ///< rotate, rad/s
  double until = 1e300;                  ///< motion stops at this time
  double release = std::numeric_limits<double>::infinity();  ///< the nodes become free at this time
};

/// Where a mesh comes from: the box or tube generator, or a .msh file.
struct SceneShape {
  std::string file;  ///< empty: box or tube generator (relative paths resolved against the scene's folder)
  bool tube = false; ///< hollow cylinder about z (mesh/tube_mesh.hpp)
  bool torus = false; ///< hollow torus about z (mesh/tube_mesh.hpp); tube_r_in/out are its tube's radii
  double torus_major_radius = 1.0;
  double tube_r_in = 0.5, tube_r_out = 1.0, tube_height = 1.0;
  bool tube_curved = true;  ///< tube, order >= 2: nodes on the circles (false: straight-sided elements)
  Eigen::Vector3d box_min = Eigen::Vector3d::Zero(), box_max = Eigen::Vector3d::Ones();
  Eigen::Vector3i cells = Eigen::Vector3i::Constant(2);  ///< box: per axis; tube: radial, around, along z; torus: radial, around z, around the tube
};

/// The embedded geometry of a finite-cell scene and its quadrature settings.
struct SceneEmbedded {
  SceneShape shape;  ///< tetrahedra (generators: Tet4)
  double drop_fraction = 1e-4;
  double stabilisation = 1e-6;
  bool simplify = true;
  /// Degree the cut cells' stiffness rules integrate exactly; < 0: the
  /// finite-cell default (FiniteCellOptions::stiffness_degree).
  int stiffness_degree = -1;
};

/// Overrides of a scene's keys, "key.path=VALUE" ("mesh.order=2",
/// "boundary.0.release=1.5", "mesh.cell=hex"): VALUE is JSON, or a string when it
/// is not valid JSON. They are applied to the JSON before validation, so an
/// overridden value is checked exactly like one in the file; a path through a
/// value that is not an object (or an array, for a numeric segment) is refused.
/// The one override mechanism of studies and the command line.
using SceneOverrides = std::vector<std::string>;

struct Scene {
  std::string file;  ///< where it was read from (for messages)
  std::string name;
  // mesh (the background when `embedded` is set)
  SceneShape mesh;
  CellType cell = CellType::Tetrahedron;
  int order = 1;
  std::optional<SceneEmbedded> embedded;
  // material
  std::string material = "neohookean";
  double young = 1e6, poisson = 0.3, density = 1000.0;
  // time stepping
  bool is_static = false;
  /// Its ProblemOptions part (solver, Newton) serves a static scene too.
  DynamicsOptions dynamics;
  double duration = 1.0;
  std::vector<SceneBoundary> boundary;
  Eigen::Vector3d initial_velocity = Eigen::Vector3d::Zero();
  int output_every = 1;
  /// Not a scene key: the command line's --reorient. The mesh builders then flip
  /// straight inverted elements of a .msh (with a warning) before validating.
  bool reorient = false;
  /// The overrides applied to the file's keys, so that an error found later (a
  /// boundary entry selecting no node of the built mesh) names the one it came from.
  SceneOverrides overrides;
  /// The scene's JSON after the overrides, as validated (keys sorted, compact):
  /// what its fingerprint (scene_fingerprint.hpp) is taken of.
  std::string resolved;
};

/// Parses and validates a scene file; throws SceneError naming the file and key.
Scene read_scene(const std::string& path, const SceneOverrides& overrides = {});
/// The same for JSON text; `origin` names it in messages.
Scene parse_scene(const std::string& text, const std::string& origin, const SceneOverrides& overrides = {});
/// `message` (an error about the scene read from `origin`) with "(the value comes
/// from the override 'K=V')" appended when one of `overrides` set the key it names;
/// unchanged when none did.
std::string name_override(const std::string& message, const std::string& origin, const SceneOverrides& overrides);

}  // namespace hofem
