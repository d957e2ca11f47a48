#include "partition_checks.hpp"

#include "mesh/box_mesh.hpp"
#include "distributed/mesh_partition.hpp"
#include "mesh/tube_mesh.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdlib>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

namespace hofem::verification {

namespace {

// Why the bounds below are exact (attained), not estimates: on these meshes RCB's
// cuts are lattice planes, so the parts are congruent blocks of lattice cells.
//
// Box, n even: the elements of cube layer i along an axis have centroids strictly
// inside that layer (Kuhn tets at 1/4, 1/2, 3/4 of the cube, hexes at 1/2), and
// every layer holds the same number of elements, so the median split along an axis
// separates the layers below n/2 from those above with no tie: the cut is the
// mid-plane. The halves (quarters) have an even number of layers along their
// longest centroid extent, an axis not yet halved, so K = 2^k gives k mid-plane
// cuts: K = 2 one plane, K = 4 one plane + two half-planes, K = 8 three planes,
// i.e. k n^2 lattice squares. Which of two equal extents rounding picks does not
// matter: the hex grid and the Kuhn triangulation (one diagonal direction) are
// unchanged by permuting the axes.
//
// Tube (parameter box r x theta x z, theta_j = 2 pi j / n_theta, n_theta % 4 == 0,
// n_z even): every element lies in one theta column of cells, so its centroid (mean
// of its vertices, which lie on the circles) is strictly on that column's side of
// the planes x = 0 and y = 0, which are lattice lines; half the columns lie on each
// side, so the median cut across x (or y: a quarter turn is a lattice shift, which
// maps the Kuhn triangulation to itself) is two half-planes theta = const of
// n_r x n_z squares. With r in [0.5, 1] and height 1.4 the centroids span ~1.8 in x
// and y but <= 1.23 in z, so the second cut (halves: ~1.8 across, ~0.9 along the
// first normal) again is a coordinate plane through the axis: quadrants. A quadrant
// spans <= 0.93 in x and y and >= 1.05 in z, so the third cut is z = 0.7: an
// annulus of n_r x n_theta squares.
constexpr double kTubeInner = 0.5, kTubeOuter = 1.0, kTubeHeight = 1.4;

struct Case {
  std::string label;
  bool tube = false;
  CellType cell = CellType::Tetrahedron;
  int order = 1;
  std::array<int, 3> cells{};  ///< box: n, n, n; tube: n_r, n_theta, n_z
};

// Cases spanning the element types (Tet4/10/20, Hex8/20) and a curved, non-box
// geometry, small enough that the group costs milliseconds.
const std::vector<Case>& cases() {
  static const std::vector<Case> c{
      {"box 8^3 Tet4", false, CellType::Tetrahedron, 1, {8, 8, 8}},
      {"box 6^3 Tet10", false, CellType::Tetrahedron, 2, {6, 6, 6}},
      {"box 4^3 Tet20", false, CellType::Tetrahedron, 3, {4, 4, 4}},
      {"box 8^3 Hex8", false, CellType::Hexahedron, 1, {8, 8, 8}},
      {"box 4^3 Hex20", false, CellType::Hexahedron, 2, {4, 4, 4}},
      {"tube 2x16x4 Tet10", true, CellType::Tetrahedron, 2, {2, 16, 4}},
      {"tube 2x16x4 Hex8", true, CellType::Hexahedron, 1, {2, 16, 4}},
  };
  return c;
}

Mesh build(const Case& c) {
  if (c.tube)
    return hollow_cylinder_mesh(kTubeInner, kTubeOuter, kTubeHeight, c.cells[0], c.cells[1], c.cells[2], c.cell,
                                c.order);
  return box_mesh(BoxSpec{{0, 0, 0}, {1, 1, 1}, c.cells}, c.cell, c.order);
}

// The partition argued above, in lattice cells: squares on the cut planes, and the
// block of part K-1 with the faces of it that are cuts.
struct IdealPartition {
  long cut_squares = 0;
  std::array<int, 3> block{};
  std::array<bool, 3> low_cut{}, high_cut{};
};

IdealPartition ideal_partition(const Case& c, int parts) {
  const int k = parts == 2 ? 1 : parts == 4 ? 2 : parts == 8 ? 3 : 0;
  const auto [a, b, z] = c.cells;
  const bool ok = k > 0 && (c.tube ? b % 4 == 0 && z % 2 == 0 : a == b && b == z && a % 2 == 0);
  if (!ok) throw std::logic_error(fmt::format("partition checks: no plane model for {} with K = {}", c.label, parts));
  IdealPartition p;
  p.block = c.cells;
  if (!c.tube) {
    // Part K-1 is on the upper side of each of its k cuts (see below).
    p.cut_squares = static_cast<long>(k) * a * a;
    for (int d = 0; d < k; ++d) p.block[d] = a / 2, p.low_cut[d] = true;
    return p;
  }
  // Halves / quadrants: a theta range of b/2 or b/4 columns, both ends cut.
  p.cut_squares = (k == 1 ? 2L : 4L) * a * z;
  p.block[1] = k == 1 ? b / 2 : b / 4;
  p.low_cut[1] = p.high_cut[1] = true;
  if (k == 3) p.cut_squares += static_cast<long>(a) * b, p.block[2] = z / 2, p.low_cut[2] = true;
  return p;
}

// Nodes of a block of lattice cells, and those on its cut faces. Tets of order p
// have a node at every point of the lattice of spacing h/p (the barycentric
// coordinates of such a point in its Kuhn tet are multiples of 1/p); Hex8 at the
// vertices; Hex20 on the lattice of spacing h/2 without face and cell centres (at
// most one half-integer coordinate). A tube block never spans 2 pi (K >= 2), so the
// seam merges none of its nodes and the parameter count is the mesh count.
std::pair<long, long> block_nodes(const Case& c, const IdealPartition& p) {
  const bool hex20 = c.cell == CellType::Hexahedron && c.order == 2;
  const int q = c.cell == CellType::Tetrahedron ? c.order : c.order == 2 ? 2 : 1;
  long total = 0, on_cut = 0;
  std::array<int, 3> i{};
  for (i[2] = 0; i[2] <= q * p.block[2]; ++i[2])
    for (i[1] = 0; i[1] <= q * p.block[1]; ++i[1])
      for (i[0] = 0; i[0] <= q * p.block[0]; ++i[0]) {
        if (hex20 && (i[0] % 2) + (i[1] % 2) + (i[2] % 2) > 1) continue;
        ++total;
        bool cut = false;
        for (int d = 0; d < 3; ++d)
          cut = cut || (p.low_cut[d] && i[d] == 0) || (p.high_cut[d] && i[d] == q * p.block[d]);
        on_cut += cut ? 1 : 0;
      }
  return {total, on_cut};
}

void check_case(Report& report, const Case& c, const Mesh& mesh, int parts) {
  const std::string label = fmt::format("{}, K={}", c.label, parts);
  const int ne = mesh.num_elements();
  const std::vector<int> part = partition_elements(mesh, parts);

  // 1. Exactly one part each: one entry per element, in [0, K).
  const long outside = std::count_if(part.begin(), part.end(), [&](int p) { return p < 0 || p >= parts; });
  report.check("partition.assignment", label,
               static_cast<double>(outside) + std::abs(static_cast<long>(part.size()) - ne), 0.0, Compare::AtMost,
               fmt::format("elements outside [0, K) + |entries - elements| ({} elements)", ne));
  if (outside > 0) return;  // partition_quality would throw
  const PartitionQuality q = partition_quality(mesh, part, parts);
  const auto [lo, hi] = std::minmax_element(q.elements.begin(), q.elements.end());

  // RCB gives each side a count proportional to the parts it will be cut into
  // (rounded down on the left), so counts differ by at most one: max <= ceil(N/K)
  // < N/K + 1, i.e. imbalance = max / (N/K) - 1 < K/N.
  report.check("partition.balance", label, q.imbalance, static_cast<double>(parts) / ne, Compare::AtMost,
               fmt::format("imbalance = max/mean - 1; elements per part {} (min {}, max {}); counts within one "
                           "=> imbalance < K/N",
                           q.elements, *lo, *hi));

  // 2. The owner is the lowest part among a node's elements: exactly one per node.
  const long owned = std::accumulate(q.owned_nodes.begin(), q.owned_nodes.end(), 0L);
  report.check(
      "partition.ownership", label, std::abs(owned - mesh.num_nodes()), 0.0, Compare::AtMost,
      fmt::format("|sum of owned nodes - nodes| ({} nodes); owned per part {}", mesh.num_nodes(), q.owned_nodes));

  // 3. Ghosts. A bisection's lower side gets the lower part numbers, so part K-1
  // is on the upper side of every cut it touches and all its cut-face nodes are
  // owned by lower parts: its ghosts are exactly those nodes. Every other part is
  // a congruent block touching as many cut faces, and its ghosts are a subset of
  // its cut-face nodes, so max ghosts / (owned + ghosts) <= on_cut / total of the
  // block, attained by part K-1.
  const IdealPartition ideal = ideal_partition(c, parts);
  const auto [total, on_cut] = block_nodes(c, ideal);
  report.check("partition.ghost_fraction", label, q.ghost_fraction,
               static_cast<double>(on_cut) / static_cast<double>(total), Compare::AtMost,
               fmt::format("max over parts of ghosts/(owned+ghosts); bound = cut-face nodes / nodes of part K-1's "
                           "block of {} cells = {}/{}; ghost nodes per part {}",
                           fmt::join(ideal.block, "x"), on_cut, total, q.ghost_nodes));

  // 4. Edge cut: the faces on the cut planes, 1 hex face or 2 tet triangles (split
  // by the Kuhn face diagonal) per lattice square. The cuts are these planes, so
  // the bound is attained; a partition that strays from them cuts more.
  const int per_square = c.cell == CellType::Tetrahedron ? 2 : 1;
  report.check("partition.cut_faces", label, q.cut_faces, static_cast<double>(ideal.cut_squares * per_square),
               Compare::AtMost,
               fmt::format("element faces shared by two parts; bound = {} squares on the cut planes x {} face(s)",
                           ideal.cut_squares, per_square));
}

}  // namespace

void add_partition_checks(Report& report) {
  const auto t0 = std::chrono::steady_clock::now();
  for (const Case& c : cases()) {
    const Mesh mesh = build(c);
    for (int parts : {2, 4, 8}) check_case(report, c, mesh, parts);
  }
  report.measure("partition.seconds", "all cases",
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
                 "meshes, partitions and quality reports of every case (the fast suite's budget: < 1 s)");
}

}  // namespace hofem::verification
