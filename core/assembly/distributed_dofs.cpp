#include "assembly/distributed_dofs.hpp"

#include "mesh/mesh_partition.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace hofem {

DistributedDofs distribute_dofs(const Mesh& mesh, const DofMap& dofs, const std::vector<int>& part, int parts) {
  if (static_cast<int>(part.size()) != mesh.num_elements() || dofs.num_dofs() != 3 * mesh.num_nodes())
    throw std::invalid_argument(fmt::format("distribute_dofs: {} parts and {} DOFs for a mesh of {} elements, {} nodes",
                                            part.size(), dofs.num_dofs(), mesh.num_elements(), mesh.num_nodes()));
  for (int p : part)
    if (p < 0 || p >= parts) throw std::invalid_argument(fmt::format("distribute_dofs: part {} outside [0, {})", p, parts));
  const std::vector<int> owner = node_owners(mesh, part);
  DistributedDofs d;
  d.parts = parts;
  d.first_row.assign(parts + 1, 0);
  d.global_row.assign(dofs.num_dofs(), -1);
  // Count each part's free DOFs, then number them part by part in DOF order.
  for (int dof = 0; dof < dofs.num_dofs(); ++dof)
    if (dofs.free_index(dof) >= 0 && owner[dof / 3] >= 0) ++d.first_row[owner[dof / 3] + 1];
  for (int p = 0; p < parts; ++p) d.first_row[p + 1] += d.first_row[p];
  std::vector<int> next(d.first_row.begin(), d.first_row.end() - 1);
  for (int dof = 0; dof < dofs.num_dofs(); ++dof)
    if (dofs.free_index(dof) >= 0 && owner[dof / 3] >= 0) d.global_row[dof] = next[owner[dof / 3]]++;
  // Ghost rows per part.
  d.ghost_rows.assign(parts, {});
  std::vector<int> seen(mesh.num_nodes(), -1);
  for (int e = 0; e < mesh.num_elements(); ++e) {
    const int p = part[e];
    for (int i = 0; i < mesh.nodes_per_element(); ++i) {
      const int n = mesh.elements(i, e);
      if (owner[n] == p || seen[n] == p) continue;
      seen[n] = p;  // elements are not grouped by part, so a node may come back: the sort below removes repeats
      for (int c = 0; c < 3; ++c)
        if (const int row = d.global_row[3 * n + c]; row >= 0) d.ghost_rows[p].push_back(row);
    }
  }
  for (auto& rows : d.ghost_rows) {
    std::sort(rows.begin(), rows.end());
    rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  }
  return d;
}

ElementRules rules_of_part(const Mesh& mesh, const std::vector<int>& part, int p, const ElementRules& base,
                           bool mass_too) {
  if (static_cast<int>(part.size()) != mesh.num_elements())
    throw std::invalid_argument(fmt::format("rules_of_part: {} parts for {} elements", part.size(), mesh.num_elements()));
  const auto none = std::make_shared<const ElementQuadrature>(
      make_element_quadrature(mesh.cell, mesh.order, Eigen::MatrixXd(3, 0), Eigen::VectorXd()));
  ElementRules rules;
  rules.stiffness.resize(mesh.num_elements());
  rules.mass.resize(mesh.num_elements());
  for (int e = 0; e < mesh.num_elements(); ++e) {
    const bool mine = part[e] == p;
    rules.stiffness[e] = !mine ? none : base.stiffness.empty() ? nullptr : base.stiffness[e];
    rules.mass[e] = !mine && mass_too ? none : base.mass.empty() ? nullptr : base.mass[e];
  }
  return rules;
}

}  // namespace hofem
