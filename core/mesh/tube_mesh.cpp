#include "mesh/tube_mesh.hpp"

#include "mesh/box_mesh.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <tuple>

namespace hofem {

Mesh hollow_cylinder_mesh(double r_in, double r_out, double height, int n_r, int n_theta, int n_z, CellType cell,
                          int order) {
  if (!(r_in > 0.0 && r_out > r_in && height > 0.0) || n_r < 1 || n_z < 1 || n_theta < 3)
    throw std::invalid_argument(fmt::format(
        "hollow_cylinder_mesh: needs 0 < r_in < r_out, height > 0, n_r, n_z >= 1, n_theta >= 3 (got r_in = {}, "
        "r_out = {}, height = {}, n = {} x {} x {})",
        r_in, r_out, height, n_r, n_theta, n_z));
  const double two_pi = 2.0 * M_PI;
  Mesh box = box_mesh(BoxSpec{{r_in, 0.0, 0.0}, {r_out, two_pi, height}, {n_r, n_theta, n_z}}, cell, order);
  // Nodes on theta = 2 pi become the theta = 0 node with the same (r, z): the
  // generator places both on the same lattice, so their (r, z) agree exactly up
  // to the rounding of the lattice arithmetic; keys are rounded to 1e-9 of the size.
  const double tol = 1e-9 * std::max(r_out, height);
  auto key = [&](int n) {
    return std::make_pair(std::llround(box.nodes(0, n) / tol), std::llround(box.nodes(2, n) / tol));
  };
  std::map<std::pair<long long, long long>, int> at_zero;
  for (int n = 0; n < box.num_nodes(); ++n)
    if (std::fabs(box.nodes(1, n)) <= 1e-12) at_zero[key(n)] = n;
  std::vector<int> target(box.num_nodes());
  for (int n = 0; n < box.num_nodes(); ++n) {
    target[n] = n;
    if (std::fabs(box.nodes(1, n) - two_pi) <= 1e-12) {
      const auto it = at_zero.find(key(n));
      if (it == at_zero.end()) throw std::logic_error("hollow_cylinder_mesh: seam node without its theta = 0 twin");
      target[n] = it->second;
    }
  }
  // Compact numbering of the kept nodes.
  std::vector<int> new_id(box.num_nodes(), -1);
  int count = 0;
  for (int n = 0; n < box.num_nodes(); ++n)
    if (target[n] == n) new_id[n] = count++;
  Mesh m;
  m.cell = box.cell;
  m.order = box.order;
  m.nodes.resize(3, count);
  for (int n = 0; n < box.num_nodes(); ++n)
    if (target[n] == n) {
      const double r = box.nodes(0, n), t = box.nodes(1, n);
      m.nodes.col(new_id[n]) << r * std::cos(t), r * std::sin(t), box.nodes(2, n);
    }
  m.elements = box.elements;
  for (Eigen::Index e = 0; e < m.elements.cols(); ++e)
    for (Eigen::Index i = 0; i < m.elements.rows(); ++i) m.elements(i, e) = new_id[target[m.elements(i, e)]];
  const std::map<std::string, std::string> rename{
      {"xmin", "inner"}, {"xmax", "outer"}, {"zmin", "bottom"}, {"zmax", "top"}};
  for (const auto& [from, to] : rename) {
    std::vector<int> nodes;
    for (int n : box.node_set(from)) nodes.push_back(new_id[target[n]]);
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    m.node_sets[to] = nodes;
  }
  std::vector<int> boundary;
  for (const char* s : {"inner", "outer", "bottom", "top"})
    boundary.insert(boundary.end(), m.node_sets[s].begin(), m.node_sets[s].end());
  std::sort(boundary.begin(), boundary.end());
  boundary.erase(std::unique(boundary.begin(), boundary.end()), boundary.end());
  m.node_sets["boundary"] = boundary;
  return m;
}

}  // namespace hofem
