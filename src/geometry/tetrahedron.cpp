#include "mfree/geometry/tetrahedron.hpp"

#include <cmath>

namespace mfree {

double tetrahedron_volume(const Tetrahedron& t) {
  return std::abs((t[1] - t[0]).dot((t[2] - t[0]).cross(t[3] - t[0]))) / 6.0;
}

Point<3> tetrahedron_centroid(const Tetrahedron& t) { return 0.25 * (t[0] + t[1] + t[2] + t[3]); }

Tensor2<3> tetrahedron_second_moments(const Tetrahedron& t) {
  const Point<3> s = t[0] + t[1] + t[2] + t[3];
  Tensor2<3> m = s * s.transpose();
  for (const Point<3>& v : t) m += v * v.transpose();
  return tetrahedron_volume(t) / 20.0 * m;
}

namespace {

/// The three tetrahedra of the prism with triangles (p0, p1, p2) and (q0, q1, q2), q_i above
/// p_i, its quadrilateral faces cut by the diagonals p1 q0, p2 q0 and p2 q1.
void add_prism(const Point<3>& p0, const Point<3>& p1, const Point<3>& p2, const Point<3>& q0,
               const Point<3>& q1, const Point<3>& q2, std::vector<Tetrahedron>& out) {
  out.push_back({p0, p1, p2, q0});
  out.push_back({p1, p2, q0, q1});
  out.push_back({p2, q0, q1, q2});
}

/// The part of t where sign (x[axis] - value) <= 0, appended to `out`.
void clip_to_half_space(const Tetrahedron& t, int axis, double value, double sign,
                        std::vector<Tetrahedron>& out) {
  std::array<double, 4> d;
  std::array<int, 4> in, outside;
  int n_in = 0, n_out = 0;
  for (int k = 0; k < 4; ++k) {
    d[k] = sign * (t[k][axis] - value);
    if (d[k] <= 0.0)
      in[n_in++] = k;
    else
      outside[n_out++] = k;
  }
  if (n_in == 4) {
    out.push_back(t);
    return;
  }
  if (n_in == 0) return;
  // The point of edge i (inside) -> o (outside) on the plane, put exactly on it.
  const auto cut = [&](int i, int o) {
    Point<3> p = t[i] + (t[o] - t[i]) * (d[i] / (d[i] - d[o]));
    p[axis] = value;
    return p;
  };
  if (n_in == 1) {
    const int a = in[0];
    out.push_back({t[a], cut(a, outside[0]), cut(a, outside[1]), cut(a, outside[2])});
  } else if (n_in == 2) {
    const int a = in[0], b = in[1], c = outside[0], e = outside[1];
    add_prism(t[a], cut(a, c), cut(a, e), t[b], cut(b, c), cut(b, e), out);
  } else {
    const int a = in[0], b = in[1], c = in[2], e = outside[0];
    add_prism(t[a], t[b], t[c], cut(a, e), cut(b, e), cut(c, e), out);
  }
}

}  // namespace

void clip_to_box(const Tetrahedron& t, const AlignedBox<3>& box, std::vector<Tetrahedron>& out) {
  std::vector<Tetrahedron> current{t}, next;
  for (int axis = 0; axis < 3; ++axis)
    for (const double sign : {-1.0, 1.0}) {
      next.clear();
      const double value = sign < 0.0 ? box.min()[axis] : box.max()[axis];
      for (const Tetrahedron& piece : current) clip_to_half_space(piece, axis, value, sign, next);
      current.swap(next);
      if (current.empty()) return;
    }
  out.insert(out.end(), current.begin(), current.end());
}

}  // namespace mfree
