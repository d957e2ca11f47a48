#include "assembly/assembler.hpp"

#include "element/element_kernel.hpp"
#include "quadrature/rule_library.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <exception>
#include <limits>
#include <mutex>
#include <type_traits>

namespace hofem {

namespace {

// Calls f with the node count as a compile-time constant where one is
// instantiated (Tet4, Hex8, Tet10, Tet20, Hex20), Eigen::Dynamic otherwise.
template <class F>
void dispatch_nodes(int n, F&& f) {
  switch (n) {
    case 4: f(std::integral_constant<int, 4>{}); break;
    case 8: f(std::integral_constant<int, 8>{}); break;
    case 10: f(std::integral_constant<int, 10>{}); break;
    case 20: f(std::integral_constant<int, 20>{}); break;
    default: f(std::integral_constant<int, Eigen::Dynamic>{}); break;
  }
}

// Runs body(ws, e) for every element, colour by colour, in parallel within a
// colour. The first exception (e.g. an inverted element) is rethrown after the
// parallel region with the element index added.
// Below this many elements a parallel region costs more than it saves (thread
// wake-up is ~10-100 us, an element ~1-50 us), and idle OpenMP threads spinning
// next to CHOLMOD's BLAS threads slow small solves down measurably.
constexpr int kMinParallelElements = 512;

// Rethrows the first error of an element loop with the element index added.
[[noreturn]] void rethrow_with_element(const std::exception_ptr& error, int element) {
  try {
    std::rethrow_exception(error);
  } catch (const ElementGeometryError& ex) {
    throw ElementGeometryError(fmt::format("element {}: {}", element, ex.what()));
  } catch (const MaterialDomainError& ex) {
    throw MaterialDomainError(fmt::format("element {}: {}", element, ex.what()));
  }
}

template <int N, class Body>
void for_each_element(const Mesh& mesh, const SparsityPattern& pattern, Body&& body) {
  std::exception_ptr error;
  int error_element = -1;
  std::mutex error_mutex;
#pragma omp parallel if (mesh.num_elements() >= kMinParallelElements)
  {
    ElementWorkspace<N> ws(mesh.nodes_per_element());
    for (const auto& colour : pattern.colours()) {
      const int count = static_cast<int>(colour.size());
#pragma omp for schedule(static)
      for (int k = 0; k < count; ++k) {
        const int e = colour[k];
        try {
          body(ws, e);
        } catch (...) {
          std::lock_guard<std::mutex> lock(error_mutex);
          if (!error || e < error_element) error = std::current_exception(), error_element = e;
        }
      }
    }
  }
  if (error) rethrow_with_element(error, error_element);
}

// Runs body(ws, e, owns) for every element with a node the calling thread
// owns (owns(node) says which): thread t of T owns the nodes whose first
// element (SparsityPattern::first_element) lies in its element range
// [t ne / T, (t + 1) ne / T), and visits elements in ascending order from the
// start of that range. The body writes only what belongs to owned nodes (matrix
// columns, force entries), so threads never write the same entry, and every
// entry receives its element contributions in ascending element order whatever
// the thread count (bitwise reproducible). Against colouring, consecutive
// elements share nodes, so the scatter's writes hit columns still in cache
// (elements of one colour share none: every colour swept the whole value
// array). An element with nodes of two owners is computed by both (the layer
// along a range boundary). Errors as for_each_element.
template <int N, class Body>
void for_each_element_by_columns(const Mesh& mesh, const SparsityPattern& pattern, Body&& body) {
  std::exception_ptr error;
  int error_element = -1;
  std::mutex error_mutex;
  const int n = mesh.nodes_per_element(), ne = mesh.num_elements();
#pragma omp parallel if (ne >= kMinParallelElements)
  {
    ElementWorkspace<N> ws(n);
    const int t = omp_get_thread_num(), T = omp_get_num_threads();
    const int begin = static_cast<int>(static_cast<std::int64_t>(ne) * t / T);
    const int end = static_cast<int>(static_cast<std::int64_t>(ne) * (t + 1) / T);
    auto owns = [&](int node) {
      const int f = pattern.first_element(node);
      return f >= begin && f < end;
    };
    for (int e = begin; e < ne; ++e) {
      bool mine = false;
      for (int i = 0; i < n && !mine; ++i) mine = owns(mesh.elements(i, e));
      if (!mine) continue;
      try {
        body(ws, e, owns);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error || e < error_element) error = std::current_exception(), error_element = e;
        break;  // later elements of this range would fail or be discarded alike
      }
    }
  }
  if (error) rethrow_with_element(error, error_element);
}

// Adds element e's Hessian (ws.hessian_entry) into the value array of a matrix
// with the pattern's structure: per node pair one stored position, the 3x3
// block's columns at steps of node j's column length, each column's 3 entries
// consecutive (SparsityPattern). Only the columns of nodes with owns(node).
template <class Workspace, class Owns>
void scatter_hessian(const SparsityPattern& pattern, const Mesh& mesh, int e, const Workspace& ws, double* values,
                     Owns&& owns) {
  const int n = pattern.nodes_per_element();
  const int* map = pattern.element_map(e);
  for (int j = 0; j < n; ++j) {
    const int node_j = mesh.elements(j, e);
    if (!owns(node_j)) continue;
    const int stride = pattern.column_length(node_j);
    const int* mj = map + j * n;
    for (int b = 0; b < 3; ++b) {
      double* column = values + static_cast<std::ptrdiff_t>(b) * stride;
      for (int i = 0; i < n; ++i)
        if (const int pos = mj[i]; pos >= 0) {
          column[pos] += ws.hessian_entry(i, 0, j, b);
          column[pos + 1] += ws.hessian_entry(i, 1, j, b);
          column[pos + 2] += ws.hessian_entry(i, 2, j, b);
        }
    }
  }
}

// Reference and current coordinates of element e's nodes (x: 3 per node).
template <int N>
void gather(const Mesh& mesh, const double* x, int e, ElementWorkspace<N>& ws) {
  for (int i = 0; i < ws.nodes(); ++i) {
    const int node = mesh.elements(i, e);
    ws.X.col(i) = mesh.nodes.col(node);
    ws.x.col(i) = Eigen::Map<const Eigen::Vector3d>(x + 3 * node);
  }
}

}  // namespace

Assembler::Assembler(const Mesh& mesh, const DofMap& dofs, int quadrature_degree)
    : mesh_(mesh), dofs_(dofs) {
  if (dofs.num_dofs() != 3 * mesh.num_nodes())
    throw std::invalid_argument(fmt::format("Assembler: DofMap has {} DOFs for {} nodes", dofs.num_dofs(), mesh.num_nodes()));
  degree_ = quadrature_degree >= 0 ? quadrature_degree : default_quadrature_degrees(mesh.cell, mesh.order).stiffness;
  rule_ = &quadrature_rule(mesh.cell, degree_);
  tab_ = &cached_tabulation(mesh.cell, mesh.order, degree_);
  if (tab_->num_basis != mesh.nodes_per_element())
    throw MeshError(fmt::format("Assembler: {} nodes per element but the order-{} basis has {}", mesh.nodes_per_element(),
                                mesh.order, tab_->num_basis));
  pattern_ = std::make_unique<SparsityPattern>(mesh, dofs);
}

namespace {
void check_rules(const Mesh& mesh, const ElementQuadratureList& per_element, const char* what) {
  if (!per_element.empty() && static_cast<int>(per_element.size()) != mesh.num_elements())
    throw std::invalid_argument(fmt::format("Assembler: {} element {} rules for {} elements", per_element.size(), what,
                                            mesh.num_elements()));
  for (size_t e = 0; e < per_element.size(); ++e)
    if (per_element[e] && (per_element[e]->rule.cell != mesh.cell ||
                           per_element[e]->tabulation.num_basis != mesh.nodes_per_element()))
      throw std::invalid_argument(fmt::format("Assembler: the {} rule of element {} is for another cell or basis", what, e));
}
}  // namespace

void Assembler::set_element_quadrature(ElementQuadratureList per_element) {
  check_rules(mesh_, per_element, "stiffness");
  element_quadrature_ = std::move(per_element);
}

void Assembler::set_element_rules(const ElementRules& rules) {
  check_rules(mesh_, rules.stiffness, "stiffness");
  check_rules(mesh_, rules.mass, "mass");
  element_quadrature_ = rules.stiffness;
  mass_quadrature_ = rules.mass;
}

std::vector<int> unsupported_nodes(const Mesh& mesh, const ElementRules& rules) {
  if (rules.empty()) return {};
  auto contributes = [](const ElementQuadratureList& list, int e) {
    return list.empty() || !list[e] || list[e]->rule.size() > 0;
  };
  std::vector<char> used(mesh.num_nodes(), 0);
  for (int e = 0; e < mesh.num_elements(); ++e)
    if (contributes(rules.stiffness, e) || contributes(rules.mass, e))
      for (int i = 0; i < mesh.nodes_per_element(); ++i) used[mesh.elements(i, e)] = 1;
  std::vector<int> nodes;
  for (int n = 0; n < mesh.num_nodes(); ++n)
    if (!used[n]) nodes.push_back(n);
  return nodes;
}

namespace {
void check_size(const Eigen::VectorXd& x, const Mesh& mesh) {
  if (x.size() != 3 * mesh.num_nodes())
    throw std::invalid_argument(fmt::format("Assembler: position vector has {} entries, expected {}", x.size(), 3 * mesh.num_nodes()));
}
}  // namespace

double Assembler::energy(const Material& mat, const Eigen::VectorXd& x) const {
  const Eigen::VectorXd per_element = element_energies(mat, x);
  double total = 0.0;  // sequential sum: reproducible whatever the thread count
  for (double v : per_element) total += v;
  return total;
}

Eigen::VectorXd Assembler::element_energies(const Material& mat, const Eigen::VectorXd& x) const {
  check_size(x, mesh_);
  Eigen::VectorXd per_element(mesh_.num_elements());
  dispatch_nodes(mesh_.nodes_per_element(), [&](auto n) {
    constexpr int N = decltype(n)::value;
    for_each_element<N>(mesh_, *pattern_, [&](ElementWorkspace<N>& ws, int e) {
      gather(mesh_, x.data(), e, ws);
      per_element[e] = element_energy(mat, tabulation_of(e), weights_of(e), ws);
    });
  });
  return per_element;
}

Eigen::VectorXd Assembler::element_volumes() const {
  Eigen::VectorXd volume(mesh_.num_elements());
  dispatch_nodes(mesh_.nodes_per_element(), [&](auto n) {
    constexpr int N = decltype(n)::value;
    for_each_element<N>(mesh_, *pattern_, [&](ElementWorkspace<N>& ws, int e) {
      gather(mesh_, mesh_.nodes.data(), e, ws);
      double v = 0.0;
      const Eigen::VectorXd& w = weights_of(e);
      for (int q = 0; q < w.size(); ++q) v += reference_gradients(tabulation_of(e), w, q, ws);
      volume[e] = v;
    });
  });
  return volume;
}

Eigen::VectorXd Assembler::element_min_det_F(const Eigen::VectorXd& x) const {
  check_size(x, mesh_);
  Eigen::VectorXd out(mesh_.num_elements());
  dispatch_nodes(mesh_.nodes_per_element(), [&](auto n) {
    constexpr int N = decltype(n)::value;
    for_each_element<N>(mesh_, *pattern_, [&](ElementWorkspace<N>& ws, int e) {
      gather(mesh_, x.data(), e, ws);
      double m = std::numeric_limits<double>::infinity();
      const Eigen::VectorXd& w = weights_of(e);
      for (int q = 0; q < w.size(); ++q) {
        reference_gradients(tabulation_of(e), w, q, ws);
        const Mat3 F = ws.x.lazyProduct(ws.dNdX);
        m = std::min(m, F.determinant());
      }
      out[e] = m;
    });
  });
  return out;
}

double Assembler::gradient(const Material& mat, const Eigen::VectorXd& x, Eigen::VectorXd& g) const {
  check_size(x, mesh_);
  g.setZero(3 * mesh_.num_nodes());
  std::vector<double> per_element(mesh_.num_elements());
  dispatch_nodes(mesh_.nodes_per_element(), [&](auto n) {
    constexpr int N = decltype(n)::value;
    for_each_element<N>(mesh_, *pattern_, [&](ElementWorkspace<N>& ws, int e) {
      gather(mesh_, x.data(), e, ws);
      per_element[e] = element_gradient(mat, tabulation_of(e), weights_of(e), ws);
      for (int i = 0; i < ws.nodes(); ++i) g.segment<3>(3 * mesh_.elements(i, e)) += ws.g.template segment<3>(3 * i);
    });
  });
  double total = 0.0;
  for (double v : per_element) total += v;
  return total;
}

double Assembler::hessian(const Material& mat, const Eigen::VectorXd& x, Eigen::VectorXd& g, SparseMatrix& K,
                          bool project) const {
  check_size(x, mesh_);
  if (K.nonZeros() != pattern_->nonzeros() || K.rows() != pattern_->size()) pattern_->shape(K);
  else pattern_->zero_values(K);
  g.setZero(3 * mesh_.num_nodes());
  double* values = K.valuePtr();
  std::vector<double> per_element(mesh_.num_elements());
  dispatch_nodes(mesh_.nodes_per_element(), [&](auto n) {
    constexpr int N = decltype(n)::value;
    for_each_element_by_columns<N>(mesh_, *pattern_, [&](ElementWorkspace<N>& ws, int e, const auto& owns) {
      gather(mesh_, x.data(), e, ws);
      const double energy = element_hessian(mat, tabulation_of(e), weights_of(e), ws, project && !mat.constant_tangent());
      if (owns(mesh_.elements(0, e))) per_element[e] = energy;  // one writer per element
      for (int i = 0; i < ws.nodes(); ++i)
        if (const int node = mesh_.elements(i, e); owns(node)) g.segment<3>(3 * node) += ws.g.template segment<3>(3 * i);
      scatter_hessian(*pattern_, mesh_, e, ws, values, owns);
    });
  });
  double total = 0.0;
  for (double v : per_element) total += v;
  return total;
}

Eigen::VectorXd Assembler::body_force_vector(const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& f,
                                             int degree) const {
  const QuadratureRule& standard_rule = quadrature_rule(mesh_.cell, degree);
  const BasisTabulation& standard_tab = cached_tabulation(mesh_.cell, mesh_.order, degree);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(3 * mesh_.num_nodes());
  dispatch_nodes(mesh_.nodes_per_element(), [&](auto n) {
    constexpr int N = decltype(n)::value;
    for_each_element<N>(mesh_, *pattern_, [&](ElementWorkspace<N>& ws, int e) {
      const bool own = !mass_quadrature_.empty() && mass_quadrature_[e];  // a cut cell's load rule
      const QuadratureRule& rule = own ? mass_quadrature_[e]->rule : standard_rule;
      const BasisTabulation& tab = own ? mass_quadrature_[e]->tabulation : standard_tab;
      gather(mesh_, mesh_.nodes.data(), e, ws);
      for (int q = 0; q < rule.size(); ++q) {
        const double wq = reference_gradients(tab, rule.weights, q, ws);
        const Eigen::Vector3d X = ws.X * tab.values.col(q);
        const Eigen::Vector3d fq = f(X);
        for (int i = 0; i < ws.nodes(); ++i) b.segment<3>(3 * mesh_.elements(i, e)) += wq * tab.values(i, q) * fq;
      }
    });
  });
  return b;
}

// Element mass matrix int rho N_i N_j over element e (scalar; the same for each
// component), with a rule of the given degree.
template <int N>
void element_mass(const QuadratureRule& rule, const BasisTabulation& tab, double density, ElementWorkspace<N>& ws,
                  Eigen::Matrix<double, N, N>& Me) {
  const int nn = ws.nodes();
  Me.setZero(nn, nn);
  for (int q = 0; q < rule.size(); ++q) {
    const double wq = density * reference_gradients(tab, rule.weights, q, ws);
    Me.noalias() += wq * tab.values.col(q).head(nn) * tab.values.col(q).head(nn).transpose();
  }
}

// Runs body(e, Me) with the element mass matrix of every element (rule of the
// given degree, or the element's own mass rule), in parallel by colour like the
// other assemblies.
template <class Body>
void for_each_element_mass(const Mesh& mesh, const SparsityPattern& pattern, const ElementQuadratureList& per_element,
                           double density, int degree, Body&& body) {
  const QuadratureRule& standard_rule = quadrature_rule(mesh.cell, degree);
  const BasisTabulation& standard_tab = cached_tabulation(mesh.cell, mesh.order, degree);
  dispatch_nodes(mesh.nodes_per_element(), [&](auto n) {
    constexpr int N = decltype(n)::value;
    for_each_element<N>(mesh, pattern, [&](ElementWorkspace<N>& ws, int e) {
      const bool own = !per_element.empty() && per_element[e];
      const QuadratureRule& rule = own ? per_element[e]->rule : standard_rule;
      const BasisTabulation& tab = own ? per_element[e]->tabulation : standard_tab;
      gather(mesh, mesh.nodes.data(), e, ws);
      // Built once per simulation (or per mass action), so the dynamic-size case may allocate here.
      Eigen::Matrix<double, N, N> Me;
      element_mass(rule, tab, density, ws, Me);
      body(e, Me);
    });
  });
}

SparseMatrix Assembler::mass_matrix(double density, int degree) const {
  SparseMatrix M = new_matrix();
  double* values = M.valuePtr();
  const int n = pattern_->nodes_per_element();
  for_each_element_mass(mesh_, *pattern_, mass_quadrature_, density, degree, [&](int e, const auto& Me) {
    const int* map = pattern_->element_map(e);
    for (int j = 0; j < n; ++j) {
      const int stride = pattern_->column_length(mesh_.elements(j, e));
      for (int i = 0; i < n; ++i)
        if (const int pos = map[j * n + i]; pos >= 0)
          for (int a = 0; a < 3; ++a) values[pos + a * stride + a] += Me(i, j);  // entry (3i + a, 3j + a)
    }
  });
  return M;
}

// The node graph of the elements (every node, constrained ones too), then the
// element masses added by colour: elements of one colour share no node, so each
// column is written by one thread at a time.
NodalMatrix Assembler::nodal_mass_matrix(double density, int degree) const {
  const int nn = mesh_.num_nodes(), ne = mesh_.num_elements(), n = mesh_.nodes_per_element();
  std::vector<int> first(static_cast<size_t>(nn) + 1, 0), incident(static_cast<size_t>(ne) * n);
  for (int e = 0; e < ne; ++e)
    for (int i = 0; i < n; ++i) ++first[mesh_.elements(i, e) + 1];
  for (int v = 0; v < nn; ++v) first[v + 1] += first[v];
  {
    std::vector<int> next(first.begin(), first.end() - 1);
    for (int e = 0; e < ne; ++e)
      for (int i = 0; i < n; ++i) incident[next[mesh_.elements(i, e)]++] = e;
  }
  NodalMatrix Ms(nn, nn);
  std::vector<int> start(static_cast<size_t>(nn) + 1, 0), rows, scratch;
  for (int v = 0; v < nn; ++v) {
    scratch.clear();
    for (int k = first[v]; k < first[v + 1]; ++k)
      for (int i = 0; i < n; ++i) scratch.push_back(mesh_.elements(i, incident[k]));
    std::sort(scratch.begin(), scratch.end());
    scratch.erase(std::unique(scratch.begin(), scratch.end()), scratch.end());
    rows.insert(rows.end(), scratch.begin(), scratch.end());
    start[v + 1] = static_cast<int>(rows.size());
  }
  Ms.resizeNonZeros(static_cast<Eigen::Index>(rows.size()));
  std::copy(start.begin(), start.end(), Ms.outerIndexPtr());
  std::copy(rows.begin(), rows.end(), Ms.innerIndexPtr());
  std::fill_n(Ms.valuePtr(), rows.size(), 0.0);
  double* values = Ms.valuePtr();
  for_each_element_mass(mesh_, *pattern_, mass_quadrature_, density, degree, [&](int e, const auto& Me) {
    for (int j = 0; j < n; ++j) {
      const int c = mesh_.elements(j, e);
      const int* col = rows.data() + start[c];
      const int len = start[c + 1] - start[c];
      for (int i = 0; i < n; ++i)
        values[start[c] + (std::lower_bound(col, col + len, mesh_.elements(i, e)) - col)] += Me(i, j);
    }
  });
  return Ms;
}

Eigen::VectorXd Assembler::lumped_mass(double density, int degree, MassLumping lumping) const {
  Eigen::VectorXd m = Eigen::VectorXd::Zero(3 * mesh_.num_nodes());
  for_each_element_mass(mesh_, *pattern_, mass_quadrature_, density, degree, [&](int e, const auto& Me) {
    // Row sums, or Hinton, Rock & Zienkiewicz (1976): the consistent diagonal
    // scaled to the element's mass. HRZ is positive for every order, where row
    // sums are not (Tet10 vertices get -m_e/20, Hex20 corners -m_e/12).
    if (Me.trace() <= 0.0) return;  // an element with an empty (cut-cell) rule: no mass
    const double hrz = Me.sum() / Me.trace();
    // Colours make the nodes of concurrently processed elements disjoint.
    for (int i = 0; i < Me.rows(); ++i)
      m.segment<3>(3 * mesh_.elements(i, e)).array() += lumping == MassLumping::RowSum ? Me.row(i).sum() : hrz * Me(i, i);
  });
  return m;
}

Eigen::VectorXd Assembler::mass_action(double density, int degree, const Eigen::VectorXd& r) const {
  check_size(r, mesh_);
  Eigen::VectorXd y = Eigen::VectorXd::Zero(3 * mesh_.num_nodes());
  for_each_element_mass(mesh_, *pattern_, mass_quadrature_, density, degree, [&](int e, const auto& Me) {
    for (int i = 0; i < Me.rows(); ++i)
      for (int j = 0; j < Me.cols(); ++j)
        y.segment<3>(3 * mesh_.elements(i, e)) += Me(i, j) * r.segment<3>(3 * mesh_.elements(j, e));
  });
  return y;
}

}  // namespace hofem
