#include "study/convergence_table.hpp"

#include "quadrature/cell_type.hpp"

#include <cmath>
#include <iterator>

namespace hofem {

double observed_rate(double error_coarse, double error_fine, double h_coarse, double h_fine) {
  return std::log(error_coarse / error_fine) / std::log(h_coarse / h_fine);
}

namespace {

using json = nlohmann::json;

// Every column once: its name, unit, meaning and value. The CSV header, the JSON
// "columns" and every row come from this list, so they cannot disagree.
struct Column {
  const char* name;
  const char* unit;
  const char* description;
  json (*value)(const ConvergenceRow&);
};

json optional_number(const std::optional<double>& v) { return v ? json(*v) : json(nullptr); }

// The manufactured problem is posed without dimensions: the unit cube, E = 1, u*
// of amplitude 1 (linear) or 0.1 (the hyperelastic materials: mms_displacement_scale); lengths are in cube sides.
constexpr Column kColumns[] = {
    {"problem", "-", "manufactured problem: the material (material_names(); linear: linear elasticity)",
     [](const ConvergenceRow& r) { return json(r.problem); }},
    {"cell", "-", "element shape: tet or hex", [](const ConvergenceRow& r) { return json(r.cell); }},
    {"order", "-", "Lagrange order p (hex: 1 = Hex8, 2 = Hex20 serendipity)",
     [](const ConvergenceRow& r) { return json(r.order); }},
    {"mesh", "-", "uniform, or perturbed (interior vertices moved at random by up to 0.1 h per coordinate)",
     [](const ConvergenceRow& r) { return json(r.mesh); }},
    {"n", "-", "cubes per side of the unit cube", [](const ConvergenceRow& r) { return json(r.n); }},
    {"h", "cube side", "cube edge length 1 / n", [](const ConvergenceRow& r) { return json(r.h); }},
    {"unknowns", "-", "free degrees of freedom (Dirichlet values eliminated)",
     [](const ConvergenceRow& r) { return json(r.unknowns); }},
    {"cells", "-", "elements of the mesh", [](const ConvergenceRow& r) { return json(r.cells); }},
    {"l2_error", "- (dimensionless problem)", "L2 norm of u_h - u* over the cube",
     [](const ConvergenceRow& r) { return json(r.l2_error); }},
    {"h1_error", "- (dimensionless problem)", "H1 seminorm of u_h - u* (L2 norm of the gradient error)",
     [](const ConvergenceRow& r) { return json(r.h1_error); }},
    {"rate_l2", "-", "log(l2_prev / l2_error) / log(h_prev / h) against the previous row of the same series "
                     "(problem, cell, order, mesh); empty for the first",
     [](const ConvergenceRow& r) { return optional_number(r.rate_l2); }},
    {"rate_h1", "-", "the same for h1_error", [](const ConvergenceRow& r) { return optional_number(r.rate_h1); }},
    {"setup_seconds", "s", "DOF map, sparsity pattern, tabulations and load vector",
     [](const ConvergenceRow& r) { return json(r.setup_seconds); }},
    {"assembly_seconds", "s", "energy, gradient and Hessian assembly",
     [](const ConvergenceRow& r) { return json(r.assembly_seconds); }},
    {"solve_seconds", "s", "linear solver: set-up (factorisation or preconditioner) and solves",
     [](const ConvergenceRow& r) { return json(r.solve_seconds); }},
    {"total_seconds", "s", "wall time of the whole run: mesh, set-up, Newton solve and error integration",
     [](const ConvergenceRow& r) { return json(r.total_seconds); }},
    {"newton_iterations", "-", "Newton iterations summed over load steps (1 for the linear problem)",
     [](const ConvergenceRow& r) { return json(r.newton_iterations); }},
    {"linear_iterations", "-", "Krylov iterations summed over the solve (0 for a direct solver)",
     [](const ConvergenceRow& r) { return json(r.linear_iterations); }},
    {"linear_solver", "-", "the linear solver used (the 'auto' choice resolved)",
     [](const ConvergenceRow& r) { return json(r.linear_solver); }},
    {"converged", "-", "Newton met its residual tolerance", [](const ConvergenceRow& r) { return json(r.converged); }},
};

// RFC 4180: a field holding a comma, a quote or a line break is quoted, its quotes doubled.
std::string csv_field(const json& v) {
  if (v.is_null()) return {};
  if (!v.is_string()) return v.dump();
  const std::string& s = v.get_ref<const std::string&>();
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string quoted = "\"";
  for (char c : s) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

bool same_series(const ConvergenceRow& a, const ConvergenceRow& b) {
  return a.problem == b.problem && a.cell == b.cell && a.order == b.order && a.mesh == b.mesh;
}

}  // namespace

const ConvergenceRow& ConvergenceTable::add(const MmsCase& c, const MmsResult& r) {
  ConvergenceRow row;
  row.problem = c.problem;
  row.cell = std::string(name(c.cell));
  row.order = c.order;
  row.mesh = c.perturbed ? "perturbed" : "uniform";
  row.n = c.n;
  row.h = r.h;
  row.unknowns = r.dofs;
  row.cells = r.cells;
  row.l2_error = r.l2_error;
  row.h1_error = r.h1_error;
  row.setup_seconds = r.setup_seconds;
  row.assembly_seconds = r.assembly_seconds;
  row.solve_seconds = r.solve_seconds;
  row.total_seconds = r.total_seconds;
  row.newton_iterations = r.newton_iterations;
  row.linear_iterations = r.linear_iterations;
  row.linear_solver = r.linear_solver;
  row.converged = r.converged;
  for (auto prev = rows_.rbegin(); prev != rows_.rend(); ++prev)
    if (same_series(*prev, row)) {
      row.rate_l2 = observed_rate(prev->l2_error, row.l2_error, prev->h, row.h);
      row.rate_h1 = observed_rate(prev->h1_error, row.h1_error, prev->h, row.h);
      break;
    }
  rows_.push_back(std::move(row));
  return rows_.back();
}

json ConvergenceTable::row_json(const ConvergenceRow& row) {
  json j = json::object();
  for (const Column& c : kColumns) j[c.name] = c.value(row);
  return j;
}

std::string ConvergenceTable::to_csv() const {
  std::string out;
  for (const Column& c : kColumns) out += std::string(out.empty() ? "" : ",") + c.name;
  out += '\n';
  for (const ConvergenceRow& row : rows_) {
    const json j = row_json(row);
    for (std::size_t i = 0; i < std::size(kColumns); ++i) {
      if (i) out += ',';
      out += csv_field(j[kColumns[i].name]);
    }
    out += '\n';
  }
  return out;
}

json ConvergenceTable::to_json() const {
  json columns = json::array(), rows = json::array();
  for (const Column& c : kColumns) columns.push_back({{"name", c.name}, {"unit", c.unit}, {"description", c.description}});
  for (const ConvergenceRow& row : rows_) rows.push_back(row_json(row));
  return {{"columns", columns}, {"rows", rows}};
}

}  // namespace hofem
