#include "mesh/tube_mesh.hpp"

#include "mesh/box_mesh.hpp"
#include "mesh/mesh_upgrade.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <map>
#include <numeric>
#include <stdexcept>
#include <tuple>

namespace hofem {

namespace {

// Merges each node on parameter coordinate `axis` = 2 pi onto its twin at 0
// (same other coordinates): the box generator places both on one lattice, so
// they agree up to the rounding of the lattice arithmetic; keys are rounded to
// 1e-9 of `size`. target[n] is the node n becomes (itself when kept).
void merge_seam(const Mesh& box, int axis, double size, std::vector<int>& target) {
  const double two_pi = 2.0 * M_PI, tol = 1e-9 * size;
  const int a = (axis + 1) % 3, b = (axis + 2) % 3;
  auto key = [&](int n) {
    return std::make_pair(std::llround(box.nodes(a, n) / tol), std::llround(box.nodes(b, n) / tol));
  };
  std::map<std::pair<long long, long long>, int> at_zero;
  for (int n = 0; n < box.num_nodes(); ++n)
    if (std::fabs(box.nodes(axis, n)) <= 1e-12) at_zero[key(n)] = n;
  for (int n = 0; n < box.num_nodes(); ++n)
    if (std::fabs(box.nodes(axis, n) - two_pi) <= 1e-12) {
      const auto it = at_zero.find(key(n));
      if (it == at_zero.end()) throw std::logic_error("periodic mesh: seam node without its twin at 0");
      target[n] = it->second;
    }
}

// The box's mesh with the seams on parameter coordinates `seams` merged (keys
// rounded to 1e-9 of `size`), nodes mapped by `map` from parameter to physical
// coordinates, and the box's face sets renamed.
template <class Map>
Mesh mapped_mesh(const Mesh& box, std::initializer_list<int> seams, double size, const Map& map,
                 const std::map<std::string, std::string>& rename) {
  std::vector<int> target(box.num_nodes());
  std::iota(target.begin(), target.end(), 0);
  for (const int axis : seams) merge_seam(box, axis, size, target);
  // Chains (a corner on both seams) resolve to their final node.
  for (int n = 0; n < box.num_nodes(); ++n)
    while (target[target[n]] != target[n]) target[n] = target[target[n]];
  std::vector<int> new_id(box.num_nodes(), -1);
  int count = 0;
  for (int n = 0; n < box.num_nodes(); ++n)
    if (target[n] == n) new_id[n] = count++;
  Mesh m;
  m.cell = box.cell;
  m.order = box.order;
  m.nodes.resize(3, count);
  for (int n = 0; n < box.num_nodes(); ++n)
    if (target[n] == n) m.nodes.col(new_id[n]) = map(Eigen::Vector3d(box.nodes.col(n)));
  m.elements = box.elements.unaryExpr([&](int n) { return new_id[target[n]]; });
  std::vector<int> boundary;
  for (const auto& [from, to] : rename) {
    std::vector<int> nodes;
    for (int n : box.node_set(from)) nodes.push_back(new_id[target[n]]);
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    boundary.insert(boundary.end(), nodes.begin(), nodes.end());
    m.node_sets[to] = nodes;
  }
  std::sort(boundary.begin(), boundary.end());
  boundary.erase(std::unique(boundary.begin(), boundary.end()), boundary.end());
  m.node_sets["boundary"] = boundary;
  return m;
}

}  // namespace

Mesh hollow_cylinder_mesh(double r_in, double r_out, double height, int n_r, int n_theta, int n_z, CellType cell,
                          int order, bool curved) {
  if (!(r_in > 0.0 && r_out > r_in && height > 0.0) || n_r < 1 || n_z < 1 || n_theta < 3)
    throw std::invalid_argument(fmt::format(
        "hollow_cylinder_mesh: needs 0 < r_in < r_out, height > 0, n_r, n_z >= 1, n_theta >= 3 (got r_in = {}, "
        "r_out = {}, height = {}, n = {} x {} x {})",
        r_in, r_out, height, n_r, n_theta, n_z));
  if (!curved && order > 1)
    return upgrade_order(hollow_cylinder_mesh(r_in, r_out, height, n_r, n_theta, n_z, cell, 1), order);
  const Mesh box = box_mesh(BoxSpec{{r_in, 0.0, 0.0}, {r_out, 2.0 * M_PI, height}, {n_r, n_theta, n_z}}, cell, order);
  return mapped_mesh(
      box, {1}, std::max(r_out, height),
      [](const Eigen::Vector3d& p) { return Eigen::Vector3d(p[0] * std::cos(p[1]), p[0] * std::sin(p[1]), p[2]); },
      {{"xmin", "inner"}, {"xmax", "outer"}, {"zmin", "bottom"}, {"zmax", "top"}});
}

Mesh hollow_torus_mesh(double major_radius, double r_in, double r_out, int n_r, int n_theta, int n_phi, CellType cell,
                       int order) {
  if (!(r_in > 0.0 && r_out > r_in && major_radius > r_out) || n_r < 1 || n_theta < 3 || n_phi < 3)
    throw std::invalid_argument(fmt::format(
        "hollow_torus_mesh: needs 0 < r_in < r_out < major radius, n_r >= 1, n_theta, n_phi >= 3 (got R = {}, "
        "r_in = {}, r_out = {}, n = {} x {} x {})",
        major_radius, r_in, r_out, n_r, n_theta, n_phi));
  const double two_pi = 2.0 * M_PI;
  const Mesh box = box_mesh(BoxSpec{{r_in, 0.0, 0.0}, {r_out, two_pi, two_pi}, {n_r, n_theta, n_phi}}, cell, order);
  return mapped_mesh(
      box, {1, 2}, major_radius,
      [R = major_radius](const Eigen::Vector3d& p) {
        const double rho = R + p[0] * std::cos(p[2]);
        return Eigen::Vector3d(rho * std::cos(p[1]), rho * std::sin(p[1]), p[0] * std::sin(p[2]));
      },
      {{"xmin", "inner"}, {"xmax", "outer"}});
}

}  // namespace hofem
