#include "commands.hpp"

#include "number_list.hpp"
#include "study/convergence_table.hpp"
#include "study/manufactured_solution.hpp"

#include "basis/reference_basis.hpp"
#include "io/atomic_file.hpp"
#include "mesh/box_mesh.hpp"
#include "io/gmsh_reader.hpp"
#include "io/input_file.hpp"
#include "distributed/mesh_partition.hpp"
#include "mesh/mesh_quality.hpp"
#include "mesh/mesh_reorient.hpp"
#include "mesh/mesh_upgrade.hpp"
#include "io/vtu_writer.hpp"
#include "material/material.hpp"
#include "quadrature/rule_library.hpp"

#include "scene/scene.hpp"
#include "scene/scene_runner.hpp"
#include "study/study.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <mpi.h>

#include "parallel/mpi_runtime.hpp"
#include "basis/element_orders.hpp"
#include <nlohmann/json.hpp>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace hofem::cli {

namespace {

// Output paths may name a directory that does not exist yet (reports/, out/...).
void ensure_parent_directory(const std::string& path) {
  if (const std::filesystem::path p(path); p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
}

}  // namespace

// --limit NAME=VALUE options, applied before any input is read (commands.hpp).
void apply_limits(const std::vector<std::string>& limits) {
  for (const std::string& l : limits) {
    try {
      set_input_limit(l);
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
  }
}

namespace {

// A unit-cube mesh of n cells per side over the caps is refused before it is built.
void check_cube_size(int n, CellType cell, int order, const char* option) {
  // In double: n^3 of an int n overflows long long (n > 2e6).
  const auto count = [](double v) { return v < 9e18 ? static_cast<long long>(v) : LLONG_MAX; };
  const double c = n, side = double(order) * n + 1.0;
  const std::string excess =
      mesh_size_excess(count(c * c * c * (cell == CellType::Tetrahedron ? 6 : 1)), count(side * side * side));
  if (!excess.empty()) throw UsageError(fmt::format("{} {}: {}", option, n, excess));
}

// An order over the cap is refused before a basis of that order is built.
void check_order(int order) {
  if (order > input_limits().order)
    throw UsageError(fmt::format("--order {} is over the cap of {} (raise it with --limit order=N)", order,
                                 input_limits().order));
}

CellType parse_cell_or_throw(const std::string& text) {
  const auto cell = parse_cell(text);
  if (!cell) throw UsageError(fmt::format("--cell: unknown cell '{}' (valid: {})", text, cell_choices()));
  return *cell;
}

nlohmann::json rule_json(const QuadratureRule& r) {
  nlohmann::json pts = nlohmann::json::array();
  for (int q = 0; q < r.size(); ++q) {
    nlohmann::json p = nlohmann::json::array();
    for (int c = 0; c < r.dim(); ++c) p.push_back(r.points(c, q));
    pts.push_back(p);
  }
  return {{"cell", std::string(name(r.cell))},
          {"degree", r.degree},
          {"id", r.id},
          {"source", r.source},
          {"points", pts},
          {"weights", std::vector<double>(r.weights.data(), r.weights.data() + r.size())}};
}

void print_rule_table(const QuadratureRule& r) {
  fmt::print("cell     {}\ndegree   {}\nrule     {}\nsource   {}\npoints   {}\nmin weight {:.3e}   min margin {:.3e}\n\n",
             name(r.cell), r.degree, r.id, r.source, r.size(), r.min_weight(), r.min_interior_margin());
  fmt::print("{:>5}", "#");
  for (int c = 0; c < r.dim(); ++c) fmt::print(" {:>24}", std::string(1, "xyz"[c]));
  fmt::print(" {:>24}\n", "weight");
  for (int q = 0; q < r.size(); ++q) {
    fmt::print("{:>5}", q);
    for (int c = 0; c < r.dim(); ++c) fmt::print(" {:>24.17g}", r.points(c, q));
    fmt::print(" {:>24.17g}\n", r.weights[q]);
  }
}

}  // namespace

int run_quadrature(const QuadratureOptions& o) {
  const CellType cell = parse_cell_or_throw(o.cell);
  if (o.list) {
    const auto& rules = tabulated_rules(cell);
    if (rules.empty()) {
      fmt::print("{}: no tabulated rules; tensor Gauss–Legendre rules of any degree are built on demand\n", name(cell));
      return 0;
    }
    fmt::print("{:<16} {:>6} {:>6} {:>8} {:>12} {:>12}  {}\n", "rule", "degree", "points", "quality", "min weight", "min margin", "source");
    for (const auto& r : rules)
      fmt::print("{:<16} {:>6} {:>6} {:>8} {:>12.3e} {:>12.3e}  {}\n", r.id, r.degree, r.size(),
                 r.positive_interior() ? "PI" : (r.all_weights_positive() ? "P-bdry" : "neg"), r.min_weight(),
                 r.min_interior_margin(), r.source);
    return 0;
  }
  if (o.degree == kUnset) throw UsageError("--degree is required (or use --list)");
  if (o.degree < 0) throw UsageError(fmt::format("--degree must be >= 0, got {}", o.degree));
  const QuadratureRule& r = quadrature_rule(cell, o.degree);
  if (o.json) fmt::print("{}\n", rule_json(r).dump());
  else print_rule_table(r);
  return 0;
}

int run_basis(const BasisOptions& o) {
  const CellType cell = parse_cell_or_throw(o.cell);
  if (o.order < 1) throw UsageError(fmt::format("--order must be >= 1, got {}", o.order));
  check_order(o.order);
  if (cell == CellType::Quadrilateral) throw UsageError("--cell: no Lagrange basis on quad yet (valid: segment, triangle, tet, hex)");
  if (!supports_order(cell, o.order))
    throw UsageError(fmt::format("--order: {} supports {}, got {}", name(cell), supported_orders(cell), o.order));
  const ReferenceBasis& b = lagrange_basis(cell, o.order);
  if (o.json) {
    nlohmann::json nodes = nlohmann::json::array();
    for (int i = 0; i < b.size(); ++i) {
      nlohmann::json p = nlohmann::json::array();
      for (int c = 0; c < b.dim(); ++c) p.push_back(b.nodes()(c, i));
      nodes.push_back(p);
    }
    fmt::print("{}\n", nlohmann::json{{"element", b.element_name()}, {"cell", std::string(name(cell))}, {"order", b.order()}, {"nodes", nodes}}.dump());
    return 0;
  }
  fmt::print("{} ({} nodes, Gmsh order, reference coordinates)\n", b.element_name(), b.size());
  for (int i = 0; i < b.size(); ++i) {
    fmt::print("{:>4}", i);
    for (int c = 0; c < b.dim(); ++c) fmt::print(" {:>10.6f}", b.nodes()(c, i));
    fmt::print("\n");
  }
  return 0;
}

int run_mesh(const MeshOptions& o) {
  if ((o.box > 0) == !o.msh.empty()) throw UsageError("give exactly one of --box N or --msh FILE");
  apply_limits(o.limits);
  if (o.reorient && o.msh.empty()) throw UsageError("--reorient repairs a mesh read with --msh");
  Mesh m;
  if (o.box > 0) {
    const CellType cell = parse_cell_or_throw(o.cell);
    if (cell != CellType::Tetrahedron && cell != CellType::Hexahedron)
      throw UsageError(fmt::format("--cell: box meshes are tet or hex, got '{}'", o.cell));
    const int order = o.order == kUnset ? 1 : o.order;
    if (!supports_order(cell, order))
      throw UsageError(fmt::format("--order: {} supports {}, got {}", name(cell), supported_orders(cell), order));
    check_order(order);
    check_cube_size(o.box, cell, order, "--box");
    m = box_mesh(unit_cube(o.box), cell, order);
  } else {
    m = read_gmsh(o.msh);
    if (o.order != kUnset && o.order != m.order) {
      if (m.order != 1) throw UsageError(fmt::format("--order: only a linear mesh can be raised, '{}' has order {}", o.msh, m.order));
      check_order(o.order);
      m = upgrade_order(m, o.order);
    }
    if (o.reorient) {
      const std::vector<int> flipped = reorient_inverted_elements(m);
      fmt::print(stderr, "hofem: warning: --reorient renumbered {} inverted element(s){}\n", flipped.size(),
                 flipped.empty() ? std::string() : ", the first " + describe_element(m, flipped.front()));
    }
  }
  validate_mesh(m);  // names the first inverted or degenerate element
  const MeshQuality q = measure_quality(m);
  const std::string element = lagrange_basis(m.cell, m.order).element_name();
  if (!o.vtu.empty()) {
    ensure_parent_directory(o.vtu);
    Eigen::MatrixXd ids(1, m.num_elements());
    for (int e = 0; e < m.num_elements(); ++e) ids(0, e) = e;
    write_vtu(o.vtu, m, {}, {{"element_id", ids}}, parse_vtu_format(o.vtu_format));
  }
  if (o.partition < 0 || o.partition > m.num_elements())
    throw UsageError(fmt::format("--partition: needs 1 .. {} parts (the elements), got {}", m.num_elements(), o.partition));
  nlohmann::json partition;
  if (o.partition > 0) {
    const std::vector<int> part = partition_elements(m, o.partition);
    const PartitionQuality pq = partition_quality(m, part, o.partition);
    // One double per ghost DOF (3 per ghost node) per exchange: a matrix-vector
    // product's halo (parallel/halo.hpp sends exactly this).
    nlohmann::json halo = nlohmann::json::array();
    for (int p = 0; p < o.partition; ++p) halo.push_back(24LL * pq.ghost_nodes[p]);
    partition = {{"parts", pq.parts},           {"method", "recursive coordinate bisection"},
                 {"elements", pq.elements},     {"owned_nodes", pq.owned_nodes},
                 {"ghost_nodes", pq.ghost_nodes}, {"cut_faces", pq.cut_faces},
                 {"imbalance", pq.imbalance},   {"ghost_fraction", pq.ghost_fraction},
                 {"halo_bytes_per_exchange", halo}};
  }
  if (o.json) {
    nlohmann::json sets = nlohmann::json::object();
    for (const auto& [n, nodes] : m.node_sets) sets[n] = nodes.size();
    nlohmann::json out{{"element", element}, {"nodes", m.num_nodes()}, {"elements", m.num_elements()},
                       {"node_sets", sets}, {"min_dihedral_degrees", q.min_dihedral_degrees},
                       {"max_dihedral_degrees", q.max_dihedral_degrees},
                       {"min_jacobian_ratio", q.min_jacobian_ratio}, {"worst_element", q.worst_element},
                       {"inverted_elements", q.inverted_elements}};
    if (!partition.is_null()) out["partition"] = partition;
    fmt::print("{}\n", out.dump());
    return 0;
  }
  fmt::print("{}: {} nodes, {} elements\n", element, m.num_nodes(), m.num_elements());
  for (const auto& [n, nodes] : m.node_sets) fmt::print("  node set {:<12} {} nodes\n", n, nodes.size());
  if (m.cell == CellType::Tetrahedron)
    fmt::print("  dihedral angles {:.2f} .. {:.2f} degrees\n", q.min_dihedral_degrees, q.max_dihedral_degrees);
  fmt::print("  min det J ratio {:.4f} (element {}), inverted elements {}\n", q.min_jacobian_ratio, q.worst_element,
             q.inverted_elements);
  if (!partition.is_null())
    fmt::print("  {} parts (RCB): elements {}, ghost nodes {}, cut faces {}, imbalance {:.3f}, ghost fraction {:.3f}\n",
               o.partition, partition["elements"].dump(), partition["ghost_nodes"].dump(), partition["cut_faces"].get<int>(),
               partition["imbalance"].get<double>(), partition["ghost_fraction"].get<double>());
  if (!o.vtu.empty()) fmt::print("  wrote {}\n", o.vtu);
  return 0;
}

namespace {

// Every (order, n) of an mms command is checked before the first run starts.
void check_mms_cases(const MmsOptions& o, CellType cell, const std::vector<int>& orders, const std::vector<int>& sizes) {
  for (int n : sizes)
    if (n < 1) throw UsageError(fmt::format("--n must be >= 1, got {}", n));
  for (int order : orders)
    if (!supports_order(cell, order))
      throw UsageError(fmt::format("--order: {} supports {}, got {}", name(cell), supported_orders(cell), order));
  apply_limits(o.limits);
  for (int order : orders) check_order(order);
  for (int order : orders)
    for (int n : sizes) check_cube_size(n, cell, order, "--n");
  if (!o.vtu.empty() && orders.size() * sizes.size() > 1)
    throw UsageError("--vtu writes one run's solution: give one --order and one --n");
  if (!o.vtu.empty()) ensure_parent_directory(o.vtu);
  if (!o.export_matrix.empty() && (orders.size() * sizes.size() > 1 || o.problem != "linear" || o.distributed))
    throw UsageError("--export-matrix writes one linear system: give --problem linear, one --order, one --n, "
                     "no --distributed (neohookean is nonlinear: one system per Newton step)");
  if (!o.export_matrix.empty()) ensure_parent_directory(o.export_matrix + ".mtx");
  if ((o.krylov != "pcg" || o.amg != "amg" || o.rigid_body_modes) && !o.distributed)
    throw UsageError("--krylov, --amg and --rigid-body-modes choose the distributed solver: add --distributed");
}

// The solver of the options, parsed and validated once for every run.
SolverSpec mms_solver(const MmsOptions& o) {
  SolverSpec spec;
  try {
    spec = SolverSpec::parse(o.solver);
  } catch (const std::invalid_argument& e) {
    throw UsageError(fmt::format("--solver: {}", e.what()));
  }
  spec.distributed = {o.krylov, o.amg, o.rigid_body_modes};
  try {
    validate(spec.distributed);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  return spec;
}

nlohmann::json mms_json(const MmsOptions& o, const MmsCase& c, const MmsResult& r, int ranks) {
  return {{"problem", o.problem}, {"cell", std::string(name(c.cell))}, {"order", c.order}, {"n", c.n},
          {"perturbed", o.perturbed}, {"h", r.h}, {"cells", r.cells}, {"nodes", r.nodes},
          {"dofs", r.dofs}, {"l2_error", r.l2_error}, {"h1_error", r.h1_error},
          {"newton_iterations", r.newton_iterations}, {"converged", r.converged},
          {"linear_solver", r.linear_solver}, {"linear_solver_reason", r.linear_solver_reason},
          {"linear_iterations", r.linear_iterations}, {"newton_rtol", r.newton_rtol},
          {"newton_residuals", r.newton_residuals},
          {"quadrature_degree", r.quadrature_degree}, {"error_quadrature_degree", r.error_degree},
          {"setup_seconds", r.setup_seconds}, {"assembly_seconds", r.assembly_seconds},
          {"solve_seconds", r.solve_seconds}, {"total_seconds", r.total_seconds},
          {"message", r.message}, {"distributed", o.distributed}, {"ranks", ranks},
          {"distributed_solver", o.distributed ? nlohmann::json{{"krylov", o.krylov}, {"amg", o.amg}, {"rigid_body_modes", o.rigid_body_modes}} : nlohmann::json()},
          {"per_rank", o.distributed ? to_json(r.ranks) : nlohmann::json::array()}};
}

void print_mms_run(const MmsOptions& o, const MmsCase& c, const MmsResult& r) {
  fmt::print("{} {} order {} n={}{}: {} cells, {} DOFs\n  L2 error {:.6e}   H1 error {:.6e}\n  Newton {} ({})\n"
             "  solver {} ({}), residual tolerance {:.1e}, {} linear iterations\n"
             "  setup {:.3f} s, assembly {:.3f} s, solve {:.3f} s, total {:.3f} s\n",
             o.problem, name(c.cell), c.order, c.n, o.perturbed ? " perturbed" : "", r.cells, r.dofs, r.l2_error, r.h1_error,
             r.newton_iterations, r.message, r.linear_solver, r.linear_solver_reason, r.newton_rtol, r.linear_iterations, r.setup_seconds, r.assembly_seconds, r.solve_seconds, r.total_seconds);
}

// The readable table of a sweep: a header, then a row per run as it finishes.
void print_mms_table_header(const MmsOptions& o, CellType cell) {
  fmt::print("{} {}{}, solver {}; rates against the previous n of the same order\n", o.problem, name(cell),
             o.perturbed ? " perturbed" : "", o.solver);
  fmt::print("{:>5} {:>4} {:>8} {:>9} {:>12} {:>7} {:>12} {:>7} {:>6} {:>7} {:>9} {:>9} {:>9}  {}\n", "order", "n", "h",
             "DOFs", "L2 error", "rate", "H1 error", "rate", "Newton", "linear", "assembly", "solve", "total", "solver");
  fmt::print("{:>5} {:>4} {:>8} {:>9} {:>12} {:>7} {:>12} {:>7} {:>6} {:>7} {:>9} {:>9} {:>9}\n", "", "", "[side]", "",
             "", "", "", "", "its", "its", "[s]", "[s]", "[s]");
}

void print_mms_table_row(const ConvergenceRow& row) {
  const auto rate = [](const std::optional<double>& v) { return v ? fmt::format("{:.2f}", *v) : std::string("-"); };
  fmt::print("{:>5} {:>4} {:>8.5f} {:>9} {:>12.4e} {:>7} {:>12.4e} {:>7} {:>6} {:>7} {:>9.3f} {:>9.3f} {:>9.3f}  {}{}\n",
             row.order, row.n, row.h, row.unknowns, row.l2_error, rate(row.rate_l2), row.h1_error, rate(row.rate_h1),
             row.newton_iterations, row.linear_iterations, row.assembly_seconds, row.solve_seconds, row.total_seconds,
             row.linear_solver, row.converged ? "" : "  (NOT converged)");
  std::fflush(stdout);  // a row as soon as its run ends: the larger runs take minutes
}

// The rank of this process and the number of ranks (1, 0 unless distributed).
std::pair<int, int> mms_ranks(bool distributed) {
  int rank = 0, ranks = 1;
  if (distributed) {  // the problem started MPI
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  }
  return {rank, ranks};
}

}  // namespace

int run_mms(const MmsOptions& o) {
  const CellType cell = parse_cell_or_throw(o.cell);
  if (cell != CellType::Tetrahedron && cell != CellType::Hexahedron)
    throw UsageError(fmt::format("--cell: mms runs on tet or hex meshes, got '{}'", o.cell));
  // The manufactured problems are the materials (material_names(), the one list).
  const std::vector<std::string> problems = material_names();
  if (std::find(problems.begin(), problems.end(), o.problem) == problems.end())
    throw UsageError(fmt::format("--problem: unknown problem '{}' (valid: {})", o.problem, fmt::join(problems, ", ")));
  const std::vector<int> sizes = parse_number_list(o.n, "--n");
  const std::vector<int> orders = parse_number_list(o.order, "--order");
  check_mms_cases(o, cell, orders, sizes);
  const SolverSpec solver = mms_solver(o);
  // One run prints as it always has; several print a table (or JSON lines) with
  // the observed rates, each n against the previous n of the same order.
  const bool sweep = orders.size() * sizes.size() > 1;
  ConvergenceTable table;
  bool all_converged = true;
  for (int order : orders)
    for (int n : sizes) {
      hofem::MmsCase c{o.problem, cell, order, n, o.perturbed, solver, o.vtu};
      c.distributed = o.distributed;
      c.export_matrix = o.export_matrix;
      c.vtu_format = parse_vtu_format(o.vtu_format);
      const hofem::MmsResult r = hofem::run_mms(c);
      all_converged = all_converged && r.converged;
      const ConvergenceRow& row = table.add(c, r);
      const auto [rank, ranks] = mms_ranks(o.distributed);
      if (rank != 0) continue;  // every rank holds the same result; one prints it
      if (sweep && !o.json && table.rows().size() == 1) print_mms_table_header(o, cell);
      if (!o.json && !sweep) print_mms_run(o, c, r);
      if (!o.json && sweep) print_mms_table_row(row);
      if (!o.json) continue;
      nlohmann::json j = mms_json(o, c, r, ranks);
      if (sweep) {  // JSON lines: one object per run
        j["rate_l2"] = row.rate_l2 ? nlohmann::json(*row.rate_l2) : nlohmann::json(nullptr);
        j["rate_h1"] = row.rate_h1 ? nlohmann::json(*row.rate_h1) : nlohmann::json(nullptr);
      }
      fmt::print("{}\n", j.dump());
      std::fflush(stdout);
    }
  return all_converged ? 0 : 1;
}

int run_scene_file(const RunOptions& o) {
  apply_limits(o.limits);
  Scene scene;
  try {
    scene = read_scene(o.scene, o.set);
  } catch (const SceneError& e) {
    throw UsageError(e.what());
  }
  scene.reorient = o.reorient;
  SceneRunOptions options;
  options.progress = true;
  options.write_frames = !o.no_frames;
  options.final_frame = o.final_frame;
  options.vtu_format = parse_vtu_format(o.vtu_format);
  options.distributed = o.distributed;
  if (!o.checkpoint_every.empty() || o.resume) {
    options.checkpoint_dir = (std::filesystem::path(o.out) / "checkpoint").string();
    options.resume = o.resume;
    options.checkpoint_every_seconds = 60.0;
    if (!o.checkpoint_every.empty()) {
      const std::string& c = o.checkpoint_every;
      const bool seconds = c.back() == 's';
      const std::string number = seconds ? c.substr(0, c.size() - 1) : c;
      char* end = nullptr;
      const double v = std::strtod(number.c_str(), &end);
      if (number.empty() || end != number.c_str() + number.size() || !(v > 0.0) || !std::isfinite(v) ||
          (!seconds && (v != std::floor(v) || v > 1e9)))
        throw UsageError(fmt::format("--checkpoint-every '{}': expected a whole number of steps (25) or seconds (60s)", c));
      options.checkpoint_every_seconds = seconds ? v : 0.0;
      options.checkpoint_every_steps = seconds ? 0 : static_cast<int>(v);
    }
  }
  options.save_state = o.save_state;
  options.save_state_key = scene.name;
  if (o.distributed) {
    ensure_hypre();
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    options.progress = rank == 0;
  }
  SceneRunResult r;
  try {
    r = run_scene(scene, o.out, options);
  } catch (const SceneError& e) {
    throw UsageError(e.what());
  }
  if (options.progress || !o.distributed)  // distributed: rank 0 reports
    fmt::print("{}: {} ({}) -> {}/stats.json\n", scene.name, r.ok ? "done" : "FAILED", r.message, o.out);
  return r.ok ? 0 : 1;
}

int run_study_file(const StudyOptions& o) {
  apply_limits(o.limits);
  Study study;
  try {
    study = read_study(o.study);
  } catch (const SceneError& e) {
    throw UsageError(e.what());
  }
  const std::string out = o.out.empty() ? "reports/studies/" + study.name : o.out;
  try {
    const nlohmann::json j = run_study(study, out, {.progress = true, .resume = o.resume, .extended = o.extended});
    fmt::print("study {}: {} runs -> {}/study.json\n", study.name, j["runs"].size(), out);
  } catch (const SceneError& e) {
    fmt::print(stderr, "hofem: error: {}\n", e.what());
    return 1;
  }
  return 0;
}

}  // namespace hofem::cli
