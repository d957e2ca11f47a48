#include "study/surface_distance.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

namespace hofem {

namespace {

// Grid cell edge in units of sqrt(mean triangle area), and a bound on cells per
// triangle (empty cells cost memory). Measured on a 2e5-triangle torus against a
// wobbled copy, 1 thread: edges 1.5 / 2 / 3 / 4 gave 1.1 / 2.2 / 5.3 / 9.9 triangles
// per non-empty cell and 640 / 560 / 520 / 530 ns per query (a 3.3e5-triangle
// sphere: 1050 / 1040 / 965 / 965). Past the 1-4 triangles per cell one would aim
// for, because the box test of a cell's entry is cheaper than visiting more cells.
constexpr double kCellEdge = 3.0;
constexpr double kMaxCellsPerTriangle = 16.0;
// Shells searched around a point's cell before the occupancy pyramid takes over
// (the same torus: 0 / 1 / 2 / 3 shells, 780 / 525 / 520 / 525 ns per query).
constexpr int kShells = 2;
// Triangles per chunk of directed_distance: the partial sums are per chunk and
// added in chunk order, so the RMS does not depend on the thread count.
constexpr long long kChunk = 512;

// Branch-free (maxsd): whether a point is beside a box is unpredictable.
inline double outside(double x, double lo, double hi) { return std::max(std::max(lo - x, x - hi), 0.0); }

template <class Lo, class Hi>
inline double squared_distance_to_box(const Eigen::Vector3d& p, const Lo& lo, const Hi& hi) {
  const double x = outside(p[0], lo[0], hi[0]), y = outside(p[1], lo[1], hi[1]), z = outside(p[2], lo[2], hi[2]);
  return x * x + y * y + z * z;
}

Eigen::Vector3d closest_point_on_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return a + t * ab;
}

// A triangle whose |ab x ac|^2 is below eps |longest edge|^4 (sine of its largest
// angle up to ~sqrt(eps) = 1.5e-8) is taken as its three edges: the face-region
// formula below loses ~eps/sin of the edge length, the edges alone miss at most
// the triangle's width ~sin times the edge length, and the two meet at sqrt(eps).
bool is_degenerate(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double longest2 = std::max({(b - a).squaredNorm(), (c - a).squaredNorm(), (c - b).squaredNorm()});
  return (b - a).cross(c - a).squaredNorm() <= std::numeric_limits<double>::epsilon() * longest2 * longest2;
}

Eigen::Vector3d closest_point_on_edges(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                       const Eigen::Vector3d& c) {
  Eigen::Vector3d best = closest_point_on_segment(p, a, b);
  for (const Eigen::Vector3d& q : {closest_point_on_segment(p, b, c), closest_point_on_segment(p, c, a)})
    if ((p - q).squaredNorm() < (p - best).squaredNorm()) best = q;
  return best;
}

// Ericson, Real-Time Collision Detection, §5.1.5 (ClosestPtPointTriangle): the
// vertex regions, then the edge regions, then the face, each decided by the signs
// of dot products with the edges. For a non-degenerate triangle only.
Eigen::Vector3d closest_point_regular(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                      const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + (d1 / (d1 - d3)) * ab;
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const double denominator = 1.0 / (va + vb + vc);
  return a + (vb * denominator) * ab + (vc * denominator) * ac;
}

// The surface's area after the checks every entry point shares.
double checked_area(const TriangleSurface& s, const char* who) {
  if (s.triangles.empty()) throw std::invalid_argument(std::string(who) + ": the surface has no triangles");
  const double area = s.area();
  if (!(area > 0.0)) throw std::invalid_argument(std::string(who) + ": the surface has zero area");
  return area;
}

Eigen::Vector3d sample(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  return (2.0 / 3.0) * a + b / 6.0 + c / 6.0;  // no b + c: it could overflow where the sample does not
}

}  // namespace

double TriangleSurface::area() const {
  if (!points.allFinite()) throw std::invalid_argument("TriangleSurface: a point is not finite");
  const long long n = points.cols();
  double sum = 0.0;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    for (int v : triangles[t])
      if (v < 0 || v >= n)
        throw std::invalid_argument("TriangleSurface: triangle " + std::to_string(t) + " has vertex index " +
                                    std::to_string(v) + ", outside [0, " + std::to_string(n) + ")");
    const auto& [i, j, k] = triangles[t];
    sum += 0.5 * (points.col(j) - points.col(i)).cross(points.col(k) - points.col(i)).norm();
  }
  return sum;
}

double SurfaceDistance::rms() const { return std::max(a_to_b.rms, b_to_a.rms); }
double SurfaceDistance::max() const { return std::max(a_to_b.max, b_to_a.max); }

Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c) {
  return is_degenerate(a, b, c) ? closest_point_on_edges(p, a, b, c) : closest_point_regular(p, a, b, c);
}

TriangleDistanceQuery::TriangleDistanceQuery(const TriangleSurface& surface) {
  const double area = checked_area(surface, "TriangleDistanceQuery");
  const std::size_t nt = surface.triangles.size();
  if (nt >= std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("TriangleDistanceQuery: too many triangles");
  triangles_.resize(nt);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& [i, j, k] = surface.triangles[t];
    Triangle& T = triangles_[t];
    T.a = surface.points.col(i), T.b = surface.points.col(j), T.c = surface.points.col(k);
    T.degenerate = is_degenerate(T.a, T.b, T.c);
    lo = lo.cwiseMin(T.a).cwiseMin(T.b).cwiseMin(T.c);
    hi = hi.cwiseMax(T.a).cwiseMax(T.b).cwiseMax(T.c);
  }
  const Eigen::Vector3d extent = hi - lo;
  double h = kCellEdge * std::sqrt(area / double(nt));
  for (;; h *= 1.25) {  // coarsen until the grid's cell count is within its bound
    n_ = (extent / h).array().ceil().max(1.0).min(double(1 << 20)).cast<int>();
    if (n_.cast<double>().prod() <= kMaxCellsPerTriangle * double(nt) + 64.0) break;
  }
  lo_ = lo;
  size_ = extent.cwiseQuotient(n_.cast<double>());
  for (int d = 0; d < 3; ++d) inv_size_[d] = extent[d] > 0.0 ? 1.0 / size_[d] : 0.0;

  bin_triangles();
  build_pyramid();
}

// Lists each triangle in the cells its bounding box touches (counted, then filled
// in place: each cell's start moves to its end and is shifted back after).
void TriangleDistanceQuery::bin_triangles() {
  // Boxes padded far beyond rounding (1e-12 of the grid) so that a triangle is
  // listed in every cell it touches however the cell index of its extremes rounds.
  const double pad = 1e-12 * size_.cwiseProduct(n_.cast<double>()).norm();
  const std::size_t cells = std::size_t(n_.x()) * n_.y() * n_.z();
  cell_start_.assign(cells + 1, 0);
  std::size_t total = 0;
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t t = 0; t < triangles_.size(); ++t) {
      const Triangle& T = triangles_[t];
      const Eigen::Vector3d box_lo = T.a.cwiseMin(T.b).cwiseMin(T.c), box_hi = T.a.cwiseMax(T.b).cwiseMax(T.c);
      const Eigen::Vector3i a = cell_of(box_lo.array() - pad), b = cell_of(box_hi.array() + pad);
      const Entry entry{box_lo, box_hi, std::uint32_t(t)};
      for (int k = a.z(); k <= b.z(); ++k)
        for (int j = a.y(); j <= b.y(); ++j)
          for (int i = a.x(); i <= b.x(); ++i) {
            const std::size_t cell = (std::size_t(k) * n_.y() + j) * n_.x() + i;
            if (pass == 0)
              ++cell_start_[cell + 1], ++total;
            else
              entries_[cell_start_[cell]++] = entry;
          }
    }
    if (pass == 1) break;
    if (total >= std::numeric_limits<std::uint32_t>::max())
      throw std::invalid_argument("TriangleDistanceQuery: too many cell entries for the grid");
    for (std::size_t c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
    entries_.resize(total);
  }
  for (std::size_t c = cells; c > 0; --c) cell_start_[c] = cell_start_[c - 1];
  cell_start_[0] = 0;
}

// Level 0 says which cells have triangles, level l + 1 which blocks of 2 x 2 x 2
// level-l blocks do, up to one block for the whole grid.
void TriangleDistanceQuery::build_pyramid() {
  level_n_ = {n_};
  occupied_.assign(1, std::vector<std::uint8_t>(cell_start_.size() - 1));
  for (std::size_t c = 0; c + 1 < cell_start_.size(); ++c) occupied_[0][c] = cell_start_[c + 1] > cell_start_[c];
  while ((level_n_.back().array() > 1).any()) {
    const Eigen::Vector3i fine = level_n_.back(), coarse = (fine.array() + 1) / 2;
    std::vector<std::uint8_t> flags(std::size_t(coarse.x()) * coarse.y() * coarse.z(), 0);
    for (int k = 0; k < fine.z(); ++k)
      for (int j = 0; j < fine.y(); ++j)
        for (int i = 0; i < fine.x(); ++i)
          if (occupied_.back()[(std::size_t(k) * fine.y() + j) * fine.x() + i])
            flags[(std::size_t(k / 2) * coarse.y() + j / 2) * coarse.x() + i / 2] = 1;
    level_n_.push_back(coarse);
    occupied_.push_back(std::move(flags));
  }
}

Eigen::Vector3i TriangleDistanceQuery::cell_of(const Eigen::Vector3d& x) const {
  // Clamped in floating point first: a point far outside the box stays representable.
  const Eigen::Array3d t = ((x - lo_).cwiseProduct(inv_size_)).array().floor();
  return t.max(0.0).min((n_.array() - 1).cast<double>()).cast<int>();
}

// The distance to the cells outside the index block [lo, hi]: they form at most six
// slabs of the grid's box, one beyond each face of the block that is not on the
// grid's boundary. This is the exact distance to that region, so it is at least the
// simple bound r * (smallest cell edge) for shell r, and it also grows for a point
// far outside the box (whose clamped home cell is on the boundary).
double TriangleDistanceQuery::unvisited_squared_distance(const Eigen::Vector3d& p, const Eigen::Vector3i& lo,
                                                         const Eigen::Vector3i& hi) const {
  const Eigen::Vector3d grid_hi = lo_ + size_.cwiseProduct(n_.cast<double>());
  double best = std::numeric_limits<double>::infinity();
  for (int d = 0; d < 3; ++d) {
    Eigen::Vector3d below_hi = grid_hi, above_lo = lo_;
    below_hi[d] = lo_[d] + lo[d] * size_[d];
    above_lo[d] = lo_[d] + (hi[d] + 1) * size_[d];
    if (lo[d] > 0) best = std::min(best, squared_distance_to_box(p, lo_, below_hi));
    if (hi[d] < n_[d] - 1) best = std::min(best, squared_distance_to_box(p, above_lo, grid_hi));
  }
  return best;
}

void TriangleDistanceQuery::visit_cell(const Eigen::Vector3d& p, int i, int j, int k, double& best2) const {
  const Eigen::Vector3d cell_lo = lo_ + size_.cwiseProduct(Eigen::Vector3d(i, j, k));
  if (squared_distance_to_box(p, cell_lo, cell_lo + size_) >= best2) return;
  const std::size_t cell = (std::size_t(k) * n_.y() + j) * n_.x() + i;
  for (std::uint32_t e = cell_start_[cell]; e < cell_start_[cell + 1]; ++e) {
    const Entry& entry = entries_[e];
    if (squared_distance_to_box(p, entry.lo, entry.hi) >= best2) continue;  // a few flops against ~40 exact ones
    const Triangle& T = triangles_[entry.triangle];
    const Eigen::Vector3d q =
        T.degenerate ? closest_point_on_edges(p, T.a, T.b, T.c) : closest_point_regular(p, T.a, T.b, T.c);
    best2 = std::min(best2, (p - q).squaredNorm());
  }
}

void TriangleDistanceQuery::visit_shell(const Eigen::Vector3d& p, const Eigen::Vector3i& home, int r,
                                        double& best2) const {
  const Eigen::Vector3i lo = (home.array() - r).max(0), hi = (home.array() + r).min(n_.array() - 1);
  for (int k = lo.z(); k <= hi.z(); ++k)
    for (int j = lo.y(); j <= hi.y(); ++j) {
      if (std::abs(k - home.z()) == r || std::abs(j - home.y()) == r) {
        for (int i = lo.x(); i <= hi.x(); ++i) visit_cell(p, i, j, k, best2);
      } else {  // inside the shell's faces in y and z: only its two x faces
        if (home.x() - r >= 0) visit_cell(p, home.x() - r, j, k, best2);
        if (home.x() + r < n_.x()) visit_cell(p, home.x() + r, j, k, best2);
      }
    }
}

// Branch and bound down the occupancy pyramid, nearest block first, for points far
// from the surface in cell units: shells would enumerate every empty cell nearer
// than the surface (points 10 to 1e6 sizes away from a 2e5-triangle torus: 0.8 ms
// and 160k cells each by shells alone, 0.07 ms this way; in its hole 0.21 vs 0.03 ms).
void TriangleDistanceQuery::search_pyramid(const Eigen::Vector3d& p, double& best2) const {
  struct Node {
    double d2;
    int level;
    Eigen::Vector3i at;
  };
  std::array<Node, 8 * 24> stack;  // <= 7 left per level of <= 21 (n <= 2^20), and 8 on top
  int top = 0;
  stack[top++] = {0.0, int(occupied_.size()) - 1, Eigen::Vector3i::Zero()};
  while (top > 0) {
    const Node node = stack[--top];
    if (node.d2 >= best2) continue;  // best2 may have dropped since the node was pushed
    if (node.level == 0) {
      visit_cell(p, node.at.x(), node.at.y(), node.at.z(), best2);
      continue;
    }
    const int l = node.level - 1;
    const Eigen::Vector3i& n = level_n_[l];
    std::array<Node, 8> children;
    int m = 0;
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector3i at = 2 * node.at + Eigen::Vector3i(c & 1, (c >> 1) & 1, c >> 2);
      if ((at.array() >= n.array()).any() || !occupied_[l][(std::size_t(at.z()) * n.y() + at.y()) * n.x() + at.x()])
        continue;
      const Eigen::Vector3i first = at * (1 << l), end = ((at.array() + 1) * (1 << l)).min(n_.array());
      const double d2 = squared_distance_to_box(p, lo_ + size_.cwiseProduct(first.cast<double>()),
                                                lo_ + size_.cwiseProduct(end.cast<double>()));
      if (d2 >= best2) continue;
      int slot = m++;  // insertion by decreasing distance, so that the nearest is pushed last
      for (; slot > 0 && children[slot - 1].d2 < d2; --slot) children[slot] = children[slot - 1];
      children[slot] = {d2, l, at};
    }
    for (int c = 0; c < m; ++c) stack[top++] = children[c];
  }
}

double TriangleDistanceQuery::distance(const Eigen::Vector3d& p) const {
  if (!p.allFinite()) throw std::invalid_argument("TriangleDistanceQuery::distance: the point is not finite");
  const Eigen::Vector3i home = cell_of(p);
  double best2 = std::numeric_limits<double>::infinity();
  for (int r = 0; r <= kShells; ++r) {  // shell r: the cells at Chebyshev index distance r from home
    visit_shell(p, home, r, best2);
    const Eigen::Vector3i lo = (home.array() - r).max(0), hi = (home.array() + r).min(n_.array() - 1);
    if ((lo.array() == 0).all() && (hi.array() == n_.array() - 1).all()) return std::sqrt(best2);
    if (best2 <= unvisited_squared_distance(p, lo, hi)) return std::sqrt(best2);
  }
  search_pyramid(p, best2);
  return std::sqrt(best2);
}

DirectedDistance directed_distance(const TriangleSurface& from, const TriangleDistanceQuery& to) {
  checked_area(from, "directed_distance");
  const long long nt = static_cast<long long>(from.triangles.size());
  const long long chunks = (nt + kChunk - 1) / kChunk;
  std::vector<double> chunk_sum(chunks, 0.0), chunk_area(chunks, 0.0);
  double max = 0.0;
  long long samples = 0;
  // The rule (2/3, 1/6, 1/6) with weights area/3 integrates quadratics exactly, so
  // sum w d^2 is a quadrature of the integral of d^2 over the triangle: exact when
  // d is affine on it (e.g. parallel offset planes), second order otherwise.
#pragma omp parallel for schedule(dynamic) reduction(max : max) reduction(+ : samples)
  for (long long c = 0; c < chunks; ++c) {
    double sum = 0.0, area = 0.0;
    for (long long t = c * kChunk; t < std::min(nt, (c + 1) * kChunk); ++t) {
      const auto& [i, j, k] = from.triangles[t];
      const Eigen::Vector3d a = from.points.col(i), b = from.points.col(j), cc = from.points.col(k);
      const double w = 0.5 * (b - a).cross(cc - a).norm() / 3.0;
      if (!(w > 0.0)) continue;  // zero area: no weight; its vertices still count for the max
      for (const Eigen::Vector3d& x : {sample(a, b, cc), sample(b, cc, a), sample(cc, a, b)}) {
        const double d = to.distance(x);
        sum += w * d * d;
        max = std::max(max, d);
      }
      area += 3.0 * w;
      samples += 3;
    }
    chunk_sum[c] = sum;
    chunk_area[c] = area;
  }
  std::vector<char> used(from.points.cols(), 0);
  for (const auto& tri : from.triangles)
    for (int v : tri) used[v] = 1;
  const long long np = from.points.cols();
#pragma omp parallel for schedule(static) reduction(max : max)
  for (long long v = 0; v < np; ++v)
    if (used[v]) max = std::max(max, to.distance(from.points.col(v)));

  DirectedDistance result;
  double sum = 0.0;
  for (long long c = 0; c < chunks; ++c) sum += chunk_sum[c], result.area += chunk_area[c];
  result.rms = std::sqrt(sum / result.area);
  result.max = max;
  result.samples = samples;
  return result;
}

SurfaceDistance surface_distance(const TriangleSurface& a, const TriangleSurface& b) {
  // The two grids are built side by side (each build is serial: ~0.05 s at 2e5
  // triangles); an exception must not leave the parallel region, so it is carried out.
  const TriangleSurface* surfaces[2] = {&a, &b};
  std::optional<TriangleDistanceQuery> queries[2];
  std::exception_ptr errors[2];
#pragma omp parallel for num_threads(2)
  for (int s = 0; s < 2; ++s) try {
      queries[s].emplace(*surfaces[s]);
    } catch (...) {
      errors[s] = std::current_exception();
    }
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
  return {directed_distance(a, *queries[1]), directed_distance(b, *queries[0])};
}

}  // namespace hofem
