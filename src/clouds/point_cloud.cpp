#include "mfree/clouds/point_cloud.hpp"

#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <random>

#include "mfree/core/error.hpp"
#include "mfree/core/memory.hpp"

namespace mfree {

const NameTable<CloudKind>& cloud_kind_names() {
  static const NameTable<CloudKind> table{{"lattice", CloudKind::lattice}, {"perturbed", CloudKind::perturbed}, {"random", CloudKind::random}};
  return table;
}

std::string_view to_string(CloudKind kind) { return cloud_kind_names().name(kind); }

namespace {

/// Steps of a lattice of nominal spacing h spanning a length L (at least one).
int steps(double length, double h) { return std::max(1, static_cast<int>(std::lround(length / h))); }

/// Inside the closed domain up to round-off: lattice coordinates such as -1 + 12.5 * 0.08
/// land 2e-17 off a boundary they are meant to lie on, and dropping that row would leave a
/// gap of a whole spacing along the edge.
bool inside_up_to_roundoff(const Domain& domain, const Vec2& p, double h) {
  if (domain.contains(p)) return true;
  const double e = 1e-9 * h;
  return domain.contains(p + Vec2(e, 0)) || domain.contains(p - Vec2(e, 0)) ||
         domain.contains(p + Vec2(0, e)) || domain.contains(p - Vec2(0, e));
}

std::vector<Vec2> lattice(const Domain& domain, double h, bool cell_centred) {
  const Box box = domain.bounding_box();
  const Vec2 size = box.size();
  const int nx = steps(size.x(), h), ny = steps(size.y(), h);
  const double hx = size.x() / nx, hy = size.y() / ny;
  const double shift = cell_centred ? 0.5 : 0.0;
  const int px = cell_centred ? nx : nx + 1, py = cell_centred ? ny : ny + 1;
  std::vector<Vec2> points;
  points.reserve(static_cast<std::size_t>(px) * py);
  for (int j = 0; j < py; ++j)
    for (int i = 0; i < px; ++i) {
      // Snap the last vertex to the box edge exactly, so boundary nodes lie on the boundary.
      const double x = (!cell_centred && i == nx) ? box.hi.x() : box.lo.x() + (i + shift) * hx;
      const double y = (!cell_centred && j == ny) ? box.hi.y() : box.lo.y() + (j + shift) * hy;
      const Vec2 p(x, y);
      if (inside_up_to_roundoff(domain, p, h)) points.push_back(p);
    }
  return points;
}

}  // namespace

std::vector<Vec2> make_cloud(const Domain& domain, const CloudSettings& s) {
  if (!(s.spacing > 0.0) || !std::isfinite(s.spacing))
    throw InputError(fmt::format("cloud: spacing must be positive, got {}", s.spacing));
  if (!(s.perturbation >= 0.0 && s.perturbation <= 1.0))
    throw InputError(fmt::format("cloud: perturbation must lie in [0, 1] (a fraction of the "
                                 "spacing), got {}",
                                 s.perturbation));
  // Counted in floating point before any point is made: no spacing overflows the index.
  const double expected = domain.bounding_box().area() / (s.spacing * s.spacing);
  if (!(expected <= std::numeric_limits<Index>::max()))
    throw InputError(fmt::format("cloud: spacing {} gives about {:.3g} points, more than the {} a cloud may hold",
                                 s.spacing, expected, std::numeric_limits<Index>::max()));
  check_memory(expected * sizeof(Vec2) * 2.0, fmt::format("a cloud of spacing {} ({:.3g} points)", s.spacing, expected));
  std::mt19937_64 rng(s.seed);
  std::uniform_real_distribution<double> unit(-0.5, 0.5);
  std::vector<Vec2> points;

  switch (s.kind) {
    case CloudKind::lattice: points = lattice(domain, s.spacing, s.cell_centred); break;
    case CloudKind::perturbed: {
      points = lattice(domain, s.spacing, s.cell_centred);
      const double amplitude = s.perturbation * s.spacing;
      for (Vec2& p : points) {
        for (int attempt = 0; attempt < 16; ++attempt) {
          const Vec2 q = p + amplitude * Vec2(unit(rng), unit(rng));
          if (domain.contains(q)) {
            p = q;
            break;
          }
        }
      }
      break;
    }
    case CloudKind::random: {
      const Box box = domain.bounding_box();
      const auto n = static_cast<std::size_t>(std::llround(domain.area() / (s.spacing * s.spacing)));
      points.reserve(n);
      std::uniform_real_distribution<double> ux(box.lo.x(), box.hi.x()), uy(box.lo.y(), box.hi.y());
      while (points.size() < n) {
        const Vec2 p(ux(rng), uy(rng));
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

std::vector<Vec2> make_quadrature_cloud(const Domain& domain, const CloudSettings& nodes,
                                        double ratio) {
  if (!(ratio >= 1.0) || !std::isfinite(ratio))
    throw InputError(fmt::format("quadrature cloud: ratio of quadrature points to nodes must be "
                                 ">= 1, got {}",
                                 ratio));
  CloudSettings q = nodes;
  q.spacing = nodes.spacing / std::sqrt(ratio);
  q.cell_centred = true;
  q.seed = nodes.seed * 0x9E3779B97F4A7C15ull + 1;  // a stream independent of the nodes'
  return make_cloud(domain, q);
}

}  // namespace mfree
