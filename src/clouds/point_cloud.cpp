#include "mfree/clouds/point_cloud.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <random>

#include "mfree/core/error.hpp"
#include "mfree/core/memory.hpp"
#include "mfree/core/parallel.hpp"
#include "mfree/geometry/crack_faces.hpp"
#include "mfree/search/cell_list.hpp"

namespace mfree {

const NameTable<CloudKind>& cloud_kind_names() {
  static const NameTable<CloudKind> table{{"lattice", CloudKind::lattice}, {"perturbed", CloudKind::perturbed}, {"random", CloudKind::random}};
  return table;
}

std::string_view to_string(CloudKind kind) { return cloud_kind_names().name(kind); }

namespace {

/// Steps of a lattice of nominal spacing h spanning a length L (at least one).
int steps(double length, double h) { return std::max(1, static_cast<int>(std::lround(length / h))); }

/// The corners and the measure of the plane and the solid bounding boxes.
Vec2 lower(const Box& b) { return b.lo; }
Vec2 upper(const Box& b) { return b.hi; }
double box_measure(const Box& b) { return b.area(); }
Point<3> lower(const AlignedBox<3>& b) { return b.min(); }
Point<3> upper(const AlignedBox<3>& b) { return b.max(); }
double box_measure(const AlignedBox<3>& b) { return b.volume(); }
double measure(const Domain& d) { return d.area(); }
double measure(const Solid& s) { return s.measure(); }

/// h^dim.
template <int dim>
double power(double h) {
  return dim == 2 ? h * h : h * h * h;
}

/// Inside the closed domain up to round-off: lattice coordinates such as -1 + 12.5 * 0.08
/// land 2e-17 off a boundary they are meant to lie on, and dropping that row would leave a
/// gap of a whole spacing along the edge.
template <int dim, class D>
bool inside_up_to_roundoff(const D& domain, const Point<dim>& p, double h) {
  if (domain.contains(p)) return true;
  const double e = 1e-9 * h;
  for (int c = 0; c < dim; ++c) {
    Point<dim> step = Point<dim>::Zero();
    step[c] = e;
    if (domain.contains(Point<dim>(p + step)) || domain.contains(Point<dim>(p - step))) return true;
  }
  return false;
}

/// The lattice points in the domain, x fastest, then y (then z).
template <int dim, class D>
std::vector<Point<dim>> lattice(const D& domain, double h, bool cell_centred) {
  const auto box = domain.bounding_box();
  const Point<dim> lo = lower(box), hi = upper(box), size = hi - lo;
  const double shift = cell_centred ? 0.5 : 0.0;
  std::array<int, dim> n, count;
  Point<dim> step;
  std::size_t total = 1;
  for (int c = 0; c < dim; ++c) {
    n[c] = steps(size[c], h);
    step[c] = size[c] / n[c];
    count[c] = cell_centred ? n[c] : n[c] + 1;
    total *= static_cast<std::size_t>(count[c]);
  }
  std::vector<Point<dim>> points;
  points.reserve(total);
  std::array<int, dim> i{};
  for (std::size_t t = 0; t < total; ++t) {
    Point<dim> p;
    // Snap the last vertex to the box's face exactly, so boundary nodes lie on the boundary.
    for (int c = 0; c < dim; ++c)
      p[c] = (!cell_centred && i[c] == n[c]) ? hi[c] : lo[c] + (i[c] + shift) * step[c];
    if (inside_up_to_roundoff<dim>(domain, p, h)) points.push_back(p);
    for (int c = 0; c < dim && ++i[c] == count[c]; ++c) i[c] = 0;  // next index, x fastest
  }
  return points;
}

template <int dim, class D>
std::vector<Point<dim>> cloud_in(const D& domain, const CloudSettings& s) {
  if (!(s.spacing > 0.0) || !std::isfinite(s.spacing))
    throw InputError(fmt::format("cloud: spacing must be positive, got {}", s.spacing));
  if (!(s.perturbation >= 0.0 && s.perturbation <= 1.0))
    throw InputError(fmt::format("cloud: perturbation must lie in [0, 1] (a fraction of the "
                                 "spacing), got {}",
                                 s.perturbation));
  // Counted in floating point before any point is made: no spacing overflows the index.
  const double expected = box_measure(domain.bounding_box()) / power<dim>(s.spacing);
  if (!(expected <= std::numeric_limits<Index>::max()))
    throw InputError(fmt::format("cloud: spacing {} gives about {:.3g} points, more than the {} a cloud may hold",
                                 s.spacing, expected, std::numeric_limits<Index>::max()));
  check_memory(expected * sizeof(Point<dim>) * 2.0,
               fmt::format("a cloud of spacing {} ({:.3g} points)", s.spacing, expected));
  // The draws of a point's coordinates go last axis first: the order of the plane clouds of
  // earlier versions, so that a seed gives the same cloud as it always did.
  std::mt19937_64 rng(s.seed);
  std::uniform_real_distribution<double> unit(-0.5, 0.5);
  std::vector<Point<dim>> points;

  switch (s.kind) {
    case CloudKind::lattice:
      points = lattice<dim>(domain, s.spacing, s.cell_centred);
      break;
    case CloudKind::perturbed: {
      points = lattice<dim>(domain, s.spacing, s.cell_centred);
      const double amplitude = s.perturbation * s.spacing;
      for (Point<dim>& p : points) {
        for (int attempt = 0; attempt < 16; ++attempt) {
          Point<dim> offset;
          for (int c = dim - 1; c >= 0; --c) offset[c] = unit(rng);  // last axis first (below)
          const Point<dim> q = p + amplitude * offset;
          if (domain.contains(q)) {
            p = q;
            break;
          }
        }
      }
      break;
    }
    case CloudKind::random: {
      const auto box = domain.bounding_box();
      const auto n = static_cast<std::size_t>(std::llround(measure(domain) / power<dim>(s.spacing)));
      points.reserve(n);
      std::array<std::uniform_real_distribution<double>, dim> u;
      for (int c = 0; c < dim; ++c)
        u[c] = std::uniform_real_distribution<double>(lower(box)[c], upper(box)[c]);
      while (points.size() < n) {
        Point<dim> p;
        for (int c = dim - 1; c >= 0; --c) p[c] = u[c](rng);
        if (domain.contains(p)) points.push_back(p);
      }
      break;
    }
  }
  if (points.empty())
    throw InputError(fmt::format("cloud: no {} point of spacing {} falls inside the domain",
                                 to_string(s.kind), s.spacing));
  return points;
}

template <int dim, class D>
std::vector<Point<dim>> quadrature_cloud_in(const D& domain, const CloudSettings& nodes, double ratio) {
  if (!(ratio >= 1.0) || !std::isfinite(ratio))
    throw InputError(fmt::format("quadrature cloud: ratio of quadrature points to nodes must be "
                                 ">= 1, got {}",
                                 ratio));
  CloudSettings q = nodes;
  q.spacing = dim == 2 ? nodes.spacing / std::sqrt(ratio) : nodes.spacing / std::cbrt(ratio);
  q.cell_centred = true;
  q.seed = nodes.seed * 0x9E3779B97F4A7C15ull + 1;  // a stream independent of the nodes'
  return cloud_in<dim>(domain, q);
}

}  // namespace

std::vector<Vec2> make_cloud(const Domain& domain, const CloudSettings& s) { return cloud_in<2>(domain, s); }
std::vector<Point<3>> make_cloud(const Solid& solid, const CloudSettings& s) { return cloud_in<3>(solid, s); }

std::vector<Vec2> make_quadrature_cloud(const Domain& domain, const CloudSettings& nodes, double ratio) {
  return quadrature_cloud_in<2>(domain, nodes, ratio);
}
std::vector<Point<3>> make_quadrature_cloud(const Solid& solid, const CloudSettings& nodes, double ratio) {
  return quadrature_cloud_in<3>(solid, nodes, ratio);
}

std::vector<double> surface_support_radii(
    const Solid& solid, const std::vector<Point<3>>& nodes, double h, double factor, int order,
    const std::function<void(const Point<3>& sample, std::vector<Index>& near)>& unseen) {
  const double reach = factor * h, wide = (factor + 0.5) * h;
  // Samples of the surface: each triangle's barycentric grid of n steps a side, n such that
  // a step is at most h / 4.
  // A tied interface's triangles are sampled on both sides (crack_offset h off the face).
  std::vector<Point<3>> samples;
  const auto sample = [&](const std::array<Point<3>, 3>& v, std::initializer_list<Point<3>> offsets) {
    const double longest = std::max({(v[1] - v[0]).norm(), (v[2] - v[1]).norm(), (v[0] - v[2]).norm()});
    const int n = std::max(1, static_cast<int>(std::ceil(longest / (0.25 * h))));
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j)
        for (const Point<3>& offset : offsets)
          samples.push_back(v[0] + (static_cast<double>(i) / n) * (v[1] - v[0]) +
                            (static_cast<double>(j) / n) * (v[2] - v[0]) + offset);
  };
  for (const SurfaceTriangle& t : solid.surface()) sample(t.vertices, {Point<3>::Zero()});
  for (const InterfaceTriangle& t : solid.interfaces()) {
    // A little inside the triangle (its rim may lie on the surface), then off it to each side.
    const Point<3> offset = crack_offset * h * t.area_normal().normalized();
    const Point<3> centroid = (t.vertices[0] + t.vertices[1] + t.vertices[2]) / 3.0;
    std::array<Point<3>, 3> inside;
    for (std::size_t v = 0; v < 3; ++v)
      inside[v] = t.vertices[v] + crack_offset * h * (centroid - t.vertices[v]).normalized();
    sample(inside, {Point<3>(-offset), offset});
  }
  const CellList<3> cells(nodes, wide);
  std::vector<char> flat(samples.size(), 0);
  parallel_blocks(static_cast<Index>(samples.size()), 1024, [&](Index b, Index e) {
    std::vector<Index> near;
    for (Index k = b; k < e; ++k) {
      const Point<3>& x = samples[static_cast<std::size_t>(k)];
      near.clear();
      cells.for_each_in_box(x, reach, [&](Index i, const Point<3>& p) {
        if ((p - x).squaredNorm() < reach * reach) near.push_back(i);
      });
      if (unseen) unseen(x, near);
      if (near.size() >= 2) {
        Point<3> mean = Point<3>::Zero();
        for (const Index i : near) mean += nodes[static_cast<std::size_t>(i)];
        mean /= static_cast<double>(near.size());
        Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
        for (const Index i : near) {
          const Point<3> p = nodes[static_cast<std::size_t>(i)] - mean;
          covariance += p * p.transpose();
        }
        const Point<3> thin =
            Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance).eigenvectors().col(0);
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (const Index i : near) {
          lo = std::min(lo, nodes[static_cast<std::size_t>(i)].dot(thin));
          hi = std::max(hi, nodes[static_cast<std::size_t>(i)].dot(thin));
        }
        if (hi - lo >= 0.75 * order * h) continue;
      }
      flat[static_cast<std::size_t>(k)] = 1;  // or nearly empty
    }
  });
  // Every node within the wider radius of a flat sample reaches it.
  std::vector<double> radii;
  for (std::size_t k = 0; k < samples.size(); ++k)
    if (flat[k]) {
      if (radii.empty()) radii.assign(nodes.size(), reach);
      cells.for_each_in_box(samples[k], wide, [&](Index i, const Point<3>& p) {
        if ((p - samples[k]).squaredNorm() < wide * wide) radii[static_cast<std::size_t>(i)] = wide;
      });
    }
  return radii;
}

}  // namespace mfree
