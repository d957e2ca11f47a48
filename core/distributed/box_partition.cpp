#include "distributed/box_partition.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace hofem {

namespace {

using Block = std::array<std::array<int, 2>, 3>;

// The bisection as a tree, to find a cube's part in O(log parts): an inner node
// sends cubes with index < cut along `axis` to `low`, the others to `high`; a
// leaf (axis -1) is part `part`.
struct Cut {
  int axis = -1, cut = 0, low = -1, high = -1, part = 0;
};

int bisect(const BoxSpec& box, const Block& block, int parts, int first, std::vector<Block>& out, std::vector<Cut>& tree) {
  const int me = static_cast<int>(tree.size());
  tree.emplace_back();
  if (parts == 1) {
    out[first] = block;
    tree[me].part = first;
    return me;
  }
  // The longest side in length; ties to the lowest axis.
  int axis = 0;
  double longest = -1.0;
  for (int c = 0; c < 3; ++c) {
    const double length = (box.upper[c] - box.lower[c]) * (block[c][1] - block[c][0]) / box.cells[c];
    if (length > longest * (1.0 + 1e-12)) longest = length, axis = c;
  }
  const int lower_parts = parts / 2, count = block[axis][1] - block[axis][0];
  const int cut = block[axis][0] + static_cast<int>(std::lround(static_cast<double>(count) * lower_parts / parts));
  if (cut <= block[axis][0] || cut >= block[axis][1])
    throw MeshError(fmt::format("box partition: {} cubes along direction {} cannot be split into {} parts", count, axis,
                                parts));
  Block low = block, high = block;
  low[axis][1] = cut;
  high[axis][0] = cut;
  const int low_node = bisect(box, low, lower_parts, first, out, tree);
  const int high_node = bisect(box, high, parts - lower_parts, first + lower_parts, out, tree);
  tree[me] = Cut{axis, cut, low_node, high_node, 0};
  return me;
}

std::vector<Block> blocks_and_tree(const BoxSpec& box, int parts, std::vector<Cut>& tree) {
  if (parts < 1) throw MeshError(fmt::format("box partition: need >= 1 parts, got {}", parts));
  std::vector<Block> out(parts);
  bisect(box, Block{{{0, box.cells[0]}, {0, box.cells[1]}, {0, box.cells[2]}}}, parts, 0, out, tree);
  return out;
}

}  // namespace

std::vector<Block> box_blocks(const BoxSpec& box, int parts) {
  std::vector<Cut> tree;
  return blocks_and_tree(box, parts, tree);
}

LocalMesh box_piece(const BoxSpec& box, CellType cell, int order, int parts, int p) {
  std::vector<Cut> tree;
  const std::vector<Block> blocks = blocks_and_tree(box, parts, tree);
  if (p < 0 || p >= parts) throw MeshError(fmt::format("box partition: part {} outside [0, {})", p, parts));
  const Block& mine = blocks[p];
  // The block's cubes as a box of its own: the same Kuhn split and node order
  // per cube as the whole box (box_tet_mesh is translation invariant).
  BoxSpec sub;
  for (int c = 0; c < 3; ++c) {
    const double h = (box.upper[c] - box.lower[c]) / box.cells[c];
    sub.lower[c] = box.lower[c] + h * mine[c][0];
    sub.upper[c] = box.lower[c] + h * mine[c][1];
    sub.cells[c] = mine[c][1] - mine[c][0];
  }
  Mesh m = box_mesh(sub, cell, order);
  const int q = order;  // lattice refinement: p for Tet(p), 1 for Hex8, 2 for Hex20
  std::array<long long, 3> points{};
  for (int c = 0; c < 3; ++c) points[c] = static_cast<long long>(q) * box.cells[c] + 1;
  // Lattice index of every node, from its coordinates (exact up to rounding far below half a lattice step).
  const int n = m.num_nodes();
  std::vector<std::array<long long, 3>> index(n);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) {
      const double step = (box.upper[c] - box.lower[c]) / (points[c] - 1);
      index[i][c] = std::llround((m.nodes(c, i) - box.lower[c]) / step);
    }
  auto id_of = [&](const std::array<long long, 3>& I) { return I[0] + points[0] * (I[1] + points[1] * I[2]); };
  // Owner: the lowest part among the cubes whose closure holds the node (up to
  // 2 per direction: a node on a cube face lies in the cubes on both sides).
  auto part_of_cube = [&](const std::array<long long, 3>& cube) {
    int node = 0;
    while (tree[node].axis >= 0) node = cube[tree[node].axis] < tree[node].cut ? tree[node].low : tree[node].high;
    return tree[node].part;
  };
  auto owner_of = [&](const std::array<long long, 3>& I) {
    std::array<std::array<long long, 2>, 3> cubes{};
    std::array<int, 3> count{};
    for (int c = 0; c < 3; ++c) {
      const long long k = I[c] / q;
      if (I[c] % q != 0) {
        cubes[c][count[c]++] = k;
        continue;
      }
      if (k - 1 >= 0) cubes[c][count[c]++] = k - 1;
      if (k < box.cells[c]) cubes[c][count[c]++] = k;
    }
    int owner = parts;
    for (int a = 0; a < count[0]; ++a)
      for (int b = 0; b < count[1]; ++b)
        for (int d = 0; d < count[2]; ++d) owner = std::min(owner, part_of_cube({cubes[0][a], cubes[1][b], cubes[2][d]}));
    return owner;
  };
  // Local nodes in ascending global id, as LocalMesh requires.
  std::vector<int> order_of(n);
  std::iota(order_of.begin(), order_of.end(), 0);
  std::sort(order_of.begin(), order_of.end(), [&](int a, int b) { return id_of(index[a]) < id_of(index[b]); });
  std::vector<int> new_id(n);
  for (int k = 0; k < n; ++k) new_id[order_of[k]] = k;
  LocalMesh local;
  local.part = p;
  local.global_nodes = points[0] * points[1] * points[2];
  local.global_elements = (cell == CellType::Tetrahedron ? 6 : 1) * box.cells[0] * box.cells[1] * box.cells[2];
  local.mesh.cell = m.cell;
  local.mesh.order = m.order;
  local.mesh.nodes.resize(3, n);
  local.global_node.resize(n);
  local.owner.resize(n);
  const char* names[3][2] = {{"xmin", "xmax"}, {"ymin", "ymax"}, {"zmin", "zmax"}};
  std::vector<int> boundary;
  for (int k = 0; k < n; ++k) {
    const auto& I = index[order_of[k]];
    local.global_node[k] = id_of(I);
    local.owner[k] = owner_of(I);
    bool on = false;
    for (int c = 0; c < 3; ++c) {
      // One formula on every rank: shared nodes get bitwise equal coordinates.
      local.mesh.nodes(c, k) = box.lower[c] + (box.upper[c] - box.lower[c]) * static_cast<double>(I[c]) / (points[c] - 1);
      if (I[c] == 0) local.mesh.node_sets[names[c][0]].push_back(k), on = true;
      if (I[c] == points[c] - 1) local.mesh.node_sets[names[c][1]].push_back(k), on = true;
    }
    if (on) boundary.push_back(k);
  }
  for (const auto& face : names)
    for (const char* name : face) local.mesh.node_sets[name];  // present even if empty on this piece
  local.mesh.node_sets["boundary"] = std::move(boundary);
  local.mesh.elements = m.elements.unaryExpr([&](int n) { return new_id[n]; });
  // Global element index: the cube's index (x fastest), times 6 tets for tets, plus the tet.
  const int per_cube = cell == CellType::Tetrahedron ? 6 : 1;
  for (int kz = mine[2][0]; kz < mine[2][1]; ++kz)
    for (int jy = mine[1][0]; jy < mine[1][1]; ++jy)
      for (int ix = mine[0][0]; ix < mine[0][1]; ++ix)
        for (int t = 0; t < per_cube; ++t)
          local.global_element.push_back(per_cube * (ix + box.cells[0] * (jy + box.cells[1] * kz)) + t);
  return local;
}

}  // namespace hofem
