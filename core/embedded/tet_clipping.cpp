#include "embedded/tet_clipping.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <cmath>
#include <stdexcept>

namespace hofem {

double Tetrahedron::volume() const {
  Eigen::Matrix3d J;
  J << v.col(1) - v.col(0), v.col(2) - v.col(0), v.col(3) - v.col(0);
  return std::abs(J.determinant()) / 6.0;
}

namespace {

Tetrahedron make(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
  Tetrahedron t;
  t.v << a, b, c, d;
  return t;
}

// Prism with triangles (a0, a1, a2) and (b0, b1, b2), ai joined to bi: 3 tets.
void split_prism(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& a2,
                 const Eigen::Vector3d& b0, const Eigen::Vector3d& b1, const Eigen::Vector3d& b2,
                 std::vector<Tetrahedron>& out, double min_volume) {
  for (const Tetrahedron& t : {make(a0, a1, a2, b0), make(a1, a2, b0, b1), make(a2, b0, b1, b2)})
    if (t.volume() > min_volume) out.push_back(t);
}

}  // namespace

void clip_tetrahedron(const Tetrahedron& t, const HalfSpace& h, std::vector<Tetrahedron>& out, double min_volume) {
  double s[4];
  int in[4], out_idx[4], n_in = 0, n_out = 0;
  for (int i = 0; i < 4; ++i) {
    s[i] = h.signed_distance(t.v.col(i));
    if (s[i] <= 0.0) in[n_in++] = i;
    else out_idx[n_out++] = i;
  }
  if (n_out == 0) {
    out.push_back(t);
    return;
  }
  if (n_in == 0) return;
  // The point where the edge from inside vertex i to outside vertex o crosses the plane.
  auto cut = [&](int i, int o) -> Eigen::Vector3d {
    const double a = s[i] / (s[i] - s[o]);  // s[i] <= 0 < s[o], so a in [0, 1)
    return t.v.col(i) + a * (t.v.col(o) - t.v.col(i));
  };
  if (n_in == 1) {
    const int a = in[0];
    const Tetrahedron piece = make(t.v.col(a), cut(a, out_idx[0]), cut(a, out_idx[1]), cut(a, out_idx[2]));
    if (piece.volume() > min_volume) out.push_back(piece);
  } else if (n_in == 3) {
    const int d = out_idx[0];
    split_prism(t.v.col(in[0]), t.v.col(in[1]), t.v.col(in[2]), cut(in[0], d), cut(in[1], d), cut(in[2], d), out,
                min_volume);
  } else {  // two in (a, b), two out (c, d): prism (a, ac, ad) - (b, bc, bd)
    const int a = in[0], b = in[1], c = out_idx[0], d = out_idx[1];
    split_prism(t.v.col(a), cut(a, c), cut(a, d), t.v.col(b), cut(b, c), cut(b, d), out, min_volume);
  }
}

std::vector<Tetrahedron> clip_tetrahedron(const Tetrahedron& t, std::span<const HalfSpace> planes,
                                          double relative_min_volume) {
  const double min_volume = relative_min_volume * t.volume();
  std::vector<Tetrahedron> pieces{t}, next;
  for (const HalfSpace& h : planes) {
    next.clear();
    for (const Tetrahedron& p : pieces) clip_tetrahedron(p, h, next, min_volume);
    pieces.swap(next);
    if (pieces.empty()) break;
  }
  return pieces;
}

ConvexPolygon clip_polygon(const ConvexPolygon& polygon, const HalfSpace& h, double on_plane) {
  ConvexPolygon out;
  const size_t n = polygon.size();
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d& a = polygon[i];
    const Eigen::Vector3d& b = polygon[(i + 1) % n];
    const double sa = h.signed_distance(a), sb = h.signed_distance(b);
    if (sa <= on_plane) out.push_back(a);
    if ((sa < -on_plane && sb > on_plane) || (sa > on_plane && sb < -on_plane))
      out.push_back(a + (sa / (sa - sb)) * (b - a));
  }
  return out;
}

std::vector<HalfSpace> box_half_spaces(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  std::vector<HalfSpace> h;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d e = Eigen::Vector3d::Unit(k);
    h.push_back({e, hi[k]});
    h.push_back({-e, -lo[k]});
  }
  return h;
}

std::vector<HalfSpace> tetrahedron_half_spaces(const Tetrahedron& t) {
  std::vector<HalfSpace> h;
  for (int f = 0; f < 4; ++f) {
    // Face opposite vertex f; the normal points away from f.
    const Eigen::Vector3d p0 = t.v.col((f + 1) % 4), p1 = t.v.col((f + 2) % 4), p2 = t.v.col((f + 3) % 4);
    Eigen::Vector3d n = (p1 - p0).cross(p2 - p0);
    const double len = n.norm();
    if (!(len > 0.0)) throw std::invalid_argument("tetrahedron_half_spaces: degenerate tetrahedron");
    n /= len;
    if (n.dot(t.v.col(f) - p0) > 0.0) n = -n;
    h.push_back({n, n.dot(p0)});
  }
  return h;
}

}  // namespace hofem
