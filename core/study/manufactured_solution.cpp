#include "study/manufactured_solution.hpp"

#include "assembly/assembler.hpp"
#include "basis/basis_tabulation.hpp"
#include "material/material.hpp"
#include "mesh/box_mesh.hpp"
#include "distributed/box_partition.hpp"
#include "parallel/mpi_runtime.hpp"
#include "mesh/mesh_upgrade.hpp"
#include "io/vtu_writer.hpp"
#include "study/mms_export.hpp"
#include "problem/static_elasticity.hpp"
#include "quadrature/rule_library.hpp"
#include "basis/quadrature_degrees.hpp"

#include <Eigen/LU>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <chrono>
#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

namespace hofem {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double q = 0.25;  // phase shift of u*_y

}  // namespace

Eigen::Vector3d ManufacturedDisplacement::value(const Eigen::Vector3d& X) const {
  const double x = X[0], y = X[1], z = X[2];
  return scale * Eigen::Vector3d(std::sin(kPi * x) * std::sin(kPi * y) * std::sin(kPi * z),
                                 0.5 * std::sin(kPi * (x + q)) * std::sin(kPi * (y + q)) * std::sin(kPi * (z + q)),
                                 0.25 * std::cos(kPi * x) * std::cos(kPi * y) * std::exp(z));
}

Eigen::Matrix3d ManufacturedDisplacement::gradient(const Eigen::Vector3d& X) const {
  const double x = X[0], y = X[1], z = X[2], p = kPi;
  const double sx = std::sin(p * x), sy = std::sin(p * y), sz = std::sin(p * z);
  const double cx = std::cos(p * x), cy = std::cos(p * y), cz = std::cos(p * z);
  const double Sx = std::sin(p * (x + q)), Sy = std::sin(p * (y + q)), Sz = std::sin(p * (z + q));
  const double Cx = std::cos(p * (x + q)), Cy = std::cos(p * (y + q)), Cz = std::cos(p * (z + q));
  const double ez = std::exp(z);
  Eigen::Matrix3d G;
  G << p * cx * sy * sz, p * sx * cy * sz, p * sx * sy * cz,                          //
      0.5 * p * Cx * Sy * Sz, 0.5 * p * Sx * Cy * Sz, 0.5 * p * Sx * Sy * Cz,          //
      -0.25 * p * sx * cy * ez, -0.25 * p * cx * sy * ez, 0.25 * cx * cy * ez;
  return scale * G;
}

void ManufacturedDisplacement::hessians(const Eigen::Vector3d& X, Eigen::Matrix3d H[3]) const {
  const double x = X[0], y = X[1], z = X[2], p = kPi, p2 = kPi * kPi;
  const double sx = std::sin(p * x), sy = std::sin(p * y), sz = std::sin(p * z);
  const double cx = std::cos(p * x), cy = std::cos(p * y), cz = std::cos(p * z);
  const double Sx = std::sin(p * (x + q)), Sy = std::sin(p * (y + q)), Sz = std::sin(p * (z + q));
  const double Cx = std::cos(p * (x + q)), Cy = std::cos(p * (y + q)), Cz = std::cos(p * (z + q));
  const double ez = std::exp(z);
  // u_x = sx sy sz
  H[0] << -p2 * sx * sy * sz, p2 * cx * cy * sz, p2 * cx * sy * cz,  //
      p2 * cx * cy * sz, -p2 * sx * sy * sz, p2 * sx * cy * cz,      //
      p2 * cx * sy * cz, p2 * sx * cy * cz, -p2 * sx * sy * sz;
  // u_y = 0.5 Sx Sy Sz
  H[1] << -p2 * Sx * Sy * Sz, p2 * Cx * Cy * Sz, p2 * Cx * Sy * Cz,  //
      p2 * Cx * Cy * Sz, -p2 * Sx * Sy * Sz, p2 * Sx * Cy * Cz,      //
      p2 * Cx * Sy * Cz, p2 * Sx * Cy * Cz, -p2 * Sx * Sy * Sz;
  H[1] *= 0.5;
  // u_z = 0.25 cx cy e^z
  H[2] << -p2 * cx * cy * ez, p2 * sx * sy * ez, -p * sx * cy * ez,  //
      p2 * sx * sy * ez, -p2 * cx * cy * ez, -p * cx * sy * ez,      //
      -p * sx * cy * ez, -p * cx * sy * ez, cx * cy * ez;
  H[2] *= 0.25;
  for (int k = 0; k < 3; ++k) H[k] *= scale;
}

Eigen::Vector3d equilibrium_body_force(const Eigen::Matrix<double, 9, 9>& A, const Eigen::Matrix3d H[3]) {
  Eigen::Vector3d f = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) f[i] -= A(i + 3 * j, k + 3 * l) * H[k](l, j);
  return f;
}

namespace {

// Moves every vertex not on the boundary by a uniform random offset of up to
// `amplitude` times the cell size per coordinate (fixed seed per size, so the
// sequence is reproducible); the result is validated by the solver set-up.
void perturb_interior_vertices(Mesh& linear, double h, double amplitude, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-amplitude * h, amplitude * h);
  std::vector<char> on_boundary(linear.num_nodes(), 0);
  for (int n : linear.node_set("boundary")) on_boundary[n] = 1;
  for (int n = 0; n < linear.num_nodes(); ++n)
    if (!on_boundary[n])
      for (int c = 0; c < 3; ++c) linear.nodes(c, n) += u(rng);
}

}  // namespace

LameParameters mms_lame() { return LameParameters::from_young_poisson(1.0, 0.3); }

double mms_displacement_scale(const std::string& problem) { return problem == "linear" ? 1.0 : 0.1; }

MmsProblem::MmsProblem(const MmsCase& c) {
  const std::vector<std::string> names = material_names();
  if (std::find(names.begin(), names.end(), c.problem) == names.end())
    throw std::invalid_argument(
        fmt::format("mms: unknown problem '{}' (valid: {})", c.problem, fmt::join(names, ", ")));
  material = make_material(c.problem, mms_lame());
  linear = material->constant_tangent();
  ustar = ManufacturedDisplacement{mms_displacement_scale(c.problem)};

  h = 1.0 / c.n;
  if (c.distributed && !c.perturbed && c.vtu.empty()) {
    // Each rank generates its own block of the cube: memory per rank ~ N / ranks.
    ensure_hypre();
    int rank = 0, ranks = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    piece = std::make_unique<DistributedMesh>(
        distribute_piece(MPI_COMM_WORLD, box_piece(unit_cube(c.n), c.cell, c.order, ranks, rank)));
  } else {
    mesh = c.cell == CellType::Tetrahedron ? box_tet_mesh(unit_cube(c.n)) : box_hex_mesh(unit_cube(c.n));
    if (c.perturbed) perturb_interior_vertices(mesh, h, 0.1, 1000u + static_cast<unsigned>(c.n));
    if (c.order > 1) mesh = upgrade_order(mesh, c.order);
  }
  const Mesh& m = piece ? piece->mesh() : mesh;

  body_force = c.body_force ? c.body_force : [this](const Eigen::Vector3d& X) {
    const Mat3 F = Mat3::Identity() + ustar.gradient(X);
    Eigen::Matrix3d H[3];
    ustar.hessians(X, H);
    return equilibrium_body_force(material->stress_derivative(F), H);
  };
  dirichlet = {{m.node_set("boundary"), [this](const Eigen::Vector3d& X) { return ustar.value(X); }}};
  // The cube's cells are affine: with linear elasticity's constant tangent the
  // stiffness is exact at 2(p - 1) on tets (basis/quadrature_degrees.hpp).
  const QuadratureDegrees degrees =
      default_quadrature_degrees(m.cell, m.order, linear ? IntegrationDomain::Affine : IntegrationDomain::Cell);
  options.quadrature_degree = degrees.stiffness;
  options.load_degree = degrees.load;
  options.solver = c.solver;
  options.distributed = c.distributed;
  // The discretisation error is >= 1e-7 relative at every size run here; the
  // nonlinear solve is converged to 1e-10 of the load so it does not pollute it.
  options.newton.rtol = 1e-10;
  if (c.solver.is_auto() && !c.distributed) {
    // A fast iterative solver: solved to the accuracy the discretisation can use.
    // The linear tolerance follows (the one linear step of a linear problem and
    // each Newton step of a nonlinear one need no more than Newton's own test).
    options.newton.rtol = mms_algebraic_tolerance(h, c.order);
    options.newton.linear_rtol = options.newton.rtol;
  }
  if (c.algebraic_rtol > 0.0) options.newton.rtol = options.newton.linear_rtol = c.algebraic_rtol;
  // Distributed solves are hypre AMG-PCG: at 1e-12 they are as good as CHOLMOD's
  // for Newton's purposes (Newton's default 1e-8 would leave the tangent
  // predictor's linear step short of the 1e-10 target, costing an extra Newton
  // iteration that the serial direct path does not take).
  if (c.distributed) options.newton.linear_rtol = 1e-12;
}

double mms_algebraic_tolerance(double h, int order) {
  return std::clamp(0.01 * std::pow(h, order + 1), 1e-10, 1e-5);
}

MmsErrors mms_errors(const Mesh& mesh, const ManufacturedDisplacement& ustar, const Eigen::VectorXd& u) {
  // Errors with a rule of degree >= p + 3, over the isoparametric map.
  MmsErrors err;
  err.degree = std::max(mesh.order + 3, 2 * mesh.order);
  const QuadratureRule& rule = quadrature_rule(mesh.cell, err.degree);
  const BasisTabulation& tab = cached_tabulation(mesh.cell, mesh.order, err.degree);
  double l2 = 0.0, h1 = 0.0;
  err.cell_l2.resize(1, mesh.num_elements());
  const int n = mesh.nodes_per_element();
  Eigen::Matrix3Xd X(3, n), U(3, n);
  for (int e = 0; e < mesh.num_elements(); ++e) {
    for (int i = 0; i < n; ++i) {
      X.col(i) = mesh.nodes.col(mesh.elements(i, e));
      U.col(i) = u.segment<3>(3 * mesh.elements(i, e));
    }
    double element_l2 = 0.0;
    for (int k = 0; k < rule.size(); ++k) {
      const Eigen::Matrix3d J = X * tab.gradient(k);
      const double w = rule.weights[k] * J.determinant();
      const Eigen::MatrixXd dNdX = tab.gradient(k) * J.inverse();
      const Eigen::Vector3d Xq = X * tab.values.col(k);
      const double e2 = w * (U * tab.values.col(k) - ustar.value(Xq)).squaredNorm();
      l2 += e2;
      element_l2 += e2;
      h1 += w * (U * dNdX - ustar.gradient(Xq)).squaredNorm();
    }
    err.cell_l2(0, e) = std::sqrt(element_l2);
  }
  err.l2 = std::sqrt(l2);
  err.h1 = std::sqrt(h1);
  return err;
}

MmsResult run_mms(const MmsCase& c) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  MmsProblem p(c);
  const Mesh& mesh = p.mesh;  // empty for a distributed piece
  const bool generated_piece = p.piece != nullptr;
  const auto owned = generated_piece
                        ? std::make_unique<StaticElasticity>(std::move(p.piece), *p.material, p.dirichlet,
                                                             p.body_force, p.options)
                        : std::make_unique<StaticElasticity>(mesh, *p.material, p.dirichlet, p.body_force, p.options);
  StaticElasticity& problem = *owned;
  const StaticReport rep = problem.solve();
  if (!c.export_matrix.empty()) export_mms_system(c, p, problem, c.export_matrix);

  MmsResult r;
  r.cells = mesh.num_elements();
  r.nodes = mesh.num_nodes();
  if (generated_piece) {  // counted over the pieces: each element once, each node by its owner
    const DistributedMesh& d = *problem.distributed_mesh();
    r.cells = static_cast<int>(d.sum(d.local.mesh.num_elements()));
    r.nodes = static_cast<int>(d.sum(d.local.owned_nodes()));
  }
  r.dofs = static_cast<int>(problem.global_free_dofs());
  r.h = p.h;
  r.newton_iterations = rep.newton_iterations;
  r.linear_iterations = rep.linear_iterations;
  r.linear_solver = rep.linear_solver;
  r.linear_solver_reason = rep.linear_solver_reason;
  r.newton_rtol = p.options.newton.rtol;
  r.residual_over_tolerance = residual_over_tolerance(rep, p.options.newton.rtol);  // serial and distributed alike
  r.converged = rep.converged;
  r.message = rep.message;
  r.setup_seconds = rep.setup_seconds;
  r.assembly_seconds = rep.assembly_seconds;
  r.solve_seconds = rep.solve_seconds;
  r.quadrature_degree = p.options.quadrature_degree;
  for (const auto& step : rep.steps)
    for (const auto& it : step.history) r.newton_residuals.push_back(it.residual);

  // Distributed: each rank integrates the error over its own elements (its
  // piece of the mesh); the squares add up over the ranks.
  const DistributedMesh* piece = problem.distributed_mesh();
  MmsErrors err = mms_errors(problem.mesh(), p.ustar, problem.displacement());
  if (piece) {
    err.l2 = std::sqrt(piece->sum(err.l2 * err.l2));
    err.h1 = std::sqrt(piece->sum(err.h1 * err.h1));
  }
  r.error_degree = err.degree;
  if (piece) r.ranks = gather_rank_stats(problem.rank_stats(), piece->comm);
  if (!c.vtu.empty()) {
    // Gathered to rank 0 for the one VTU only (a piece run never gathers: no rank
    // would hold a whole-mesh field).
    const Eigen::VectorXd u = piece ? piece->gather_nodal(problem.displacement()) : problem.displacement();
    if (piece) err.cell_l2 = piece->gather_elemental(err.cell_l2.row(0).transpose()).transpose();
    if (!piece || piece->rank == 0) {
      Eigen::MatrixXd disp = Eigen::Map<const Eigen::MatrixXd>(u.data(), 3, mesh.num_nodes());
      Eigen::MatrixXd exact(3, mesh.num_nodes());
      for (int i = 0; i < mesh.num_nodes(); ++i) exact.col(i) = p.ustar.value(mesh.nodes.col(i));
      write_vtu(c.vtu, mesh, {{"displacement", disp}, {"exact_displacement", exact}}, {{"l2_error", err.cell_l2}},
                c.vtu_format);
    }
  }
  r.l2_error = err.l2;
  r.h1_error = err.h1;
  r.total_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return r;
}

}  // namespace hofem
